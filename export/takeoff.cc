#include "export/takeoff.h"

#include "core/error.h"
#include "core/geoid.h"
#include "core/number_format.h"

namespace cinepath::exporter {

HomeSpec TakeoffOnGround(const Trajectory& plan, const Geodetic& scene_origin, const Ground& ground) {
  if (plan.samples.empty()) throw InputError("the plan has no samples: no take-off point");
  const EnuFrame scene(scene_origin);
  const EnuFrame plan_frame(plan.origin.value_or(scene_origin));
  const Geodetic start = plan_frame.GeodeticFromEnu(plan.samples.front().position_enu_m);
  const Eigen::Vector3d start_enu = scene.EnuFromGeodetic(start);
  const std::optional<double> ground_up = ground.SurfaceUpM(start_enu.x(), start_enu.y());
  if (!ground_up) {
    throw InputError(ground.source() + ": no ground under the plan's first sample (" + FormatFixed(start_enu.x(), 1) +
                     ", " + FormatFixed(start_enu.y(), 1) + " m ENU) to take off from; pass `home` (--home)");
  }
  const Geodetic takeoff = scene.GeodeticFromEnu(Eigen::Vector3d(start_enu.x(), start_enu.y(), *ground_up));
  return HomeSpec{takeoff.lat_deg, takeoff.lon_deg,
                  Egm96Geoid::Default().AmslFromEllipsoidalM(takeoff.lat_deg, takeoff.lon_deg, takeoff.height_m)};
}

std::optional<HomeGroundCheck> CheckHomeAgainstGround(const HomeSpec& home, const Geodetic& scene_origin,
                                                      const Ground& ground) {
  const EnuFrame scene(scene_origin);
  const Egm96Geoid& geoid = Egm96Geoid::Default();
  const double home_ellipsoidal_m = geoid.EllipsoidalFromAmslM(home.lat_deg, home.lon_deg, home.amsl_m);
  const Eigen::Vector3d home_enu = scene.EnuFromGeodetic(Geodetic{home.lat_deg, home.lon_deg, home_ellipsoidal_m});
  const std::optional<double> ground_up = ground.SurfaceUpM(home_enu.x(), home_enu.y());
  if (!ground_up) return std::nullopt;
  const Geodetic ground_point = scene.GeodeticFromEnu(Eigen::Vector3d(home_enu.x(), home_enu.y(), *ground_up));
  HomeGroundCheck check;
  check.ground_amsl_m = geoid.AmslFromEllipsoidalM(ground_point.lat_deg, ground_point.lon_deg, ground_point.height_m);
  check.difference_m = home.amsl_m - check.ground_amsl_m;
  return check;
}

}  // namespace cinepath::exporter
