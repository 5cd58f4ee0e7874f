// Prints, as JSON, the first waypoint of the sample ORBIT plan moved to 25 origins around the globe,
// with the AMSL and ellipsoidal heights the exporter computed (export/mission_builder.h), for
// check_geoid.cjs to compare with npm egm96-universal.
#include <iostream>

#include "../../export/sample_trajectories.h"
#include "core/json.h"
#include "export/mission_builder.h"

int main() {
  using namespace cinepath;
  const double places[][2] = {{47.3977419, 8.545594}, {0, 0},
                              {27.9881, 86.925},      {-33.8688, 151.2093},
                              {40.7128, -74.006},     {-22.9068, -43.1729},
                              {64.1466, -21.9426},    {35.6762, 139.6503},
                              {-54.8019, -68.303},    {19.4326, -99.1332},
                              {1.3521, 103.8198},     {-1.2921, 36.8219},
                              {78.2232, 15.6267},     {-77.846, 166.676},
                              {55.7558, 37.6173},     {-4.0383, 21.7587},
                              {30.0444, 31.2357},     {-13.1631, -72.545},
                              {21.3069, -157.8583},   {61.2181, -149.9003},
                              {-41.2865, 174.7762},   {12.9716, 77.5946},
                              {-8.7832, -124.5085},   {45.0, 179.9},
                              {-45.0, -179.9}};
  Json out = Json::array();
  for (const auto& place : places) {
    Trajectory plan = exporter::testing::OrbitPlan(2, 5);
    plan.origin = Geodetic{place[0], place[1], 100.0};
    const exporter::Mission m = exporter::BuildMission(plan, exporter::MissionBuildOptions{});
    const auto& wp = m.waypoints.front();
    out.push_back(Json{{"lat_deg", wp.lat_deg},
                       {"lon_deg", wp.lon_deg},
                       {"amsl_m", wp.amsl_m},
                       {"ellipsoidal_height_m", wp.ellipsoidal_height_m}});
  }
  std::cout << DumpJson(out);
  return 0;
}
