#include "export/dji_msdk_json.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "core/json.h"
#include "export/mission_builder.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

TEST(DjiMsdkJson, FieldsAndRanges) {
  const Mission mission = BuildMission(testing::OrbitPlan(), MissionBuildOptions{});
  const MsdkJson out = WriteDjiMsdkJson(mission);
  const Json j = Json::parse(out.text);
  ASSERT_EQ(j["waypoints"].size(), mission.waypoints.size());
  EXPECT_EQ(j["headingMode"], "USING_WAYPOINT_HEADING");
  for (size_t i = 0; i < mission.waypoints.size(); ++i) {
    const Json& w = j["waypoints"][i];
    EXPECT_NEAR(w["latitude"].get<double>(), mission.waypoints[i].lat_deg, 1e-9);
    EXPECT_NEAR(w["altitude"].get<double>(), mission.waypoints[i].relative_alt_m, 1e-3);
    EXPECT_GE(w["heading"].get<double>(), -180.0);
    EXPECT_LE(w["heading"].get<double>(), 180.0);
    EXPECT_NEAR(AngleDiffDeg(w["heading"].get<double>(), mission.waypoints[i].heading_deg), 0, 0.01);
  }
  EXPECT_EQ(j["waypoints"][0]["actions"][0]["type"], "START_RECORD");
  EXPECT_EQ(out.notes.size(), 4u);
}

}  // namespace
}  // namespace cinepath::exporter
