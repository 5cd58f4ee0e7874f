#include "export/validation.h"
#include "export/formats.h"

#include <gtest/gtest.h>

#include "core/drone_profiles.h"

#include "export/mission_builder.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

TEST(Validation, CleanMissionPasses) {
  const Mission m = BuildMission(testing::OrbitPlan(), MissionBuildOptions{});
  for (Format f : {Format::kQgcPlan, Format::kDjiWpml, Format::kDjiMsdkJson, Format::kLitchiCsv}) {
    EXPECT_TRUE(ValidateMission(m, f, *FindDroneProfile("px4-multirotor"), 50).empty()) << FormatName(f);
  }
}

TEST(Validation, OverSpeedNamesWaypointAndLimit) {
  // The flyby at 10 m/s, time-compressed 2x: 20 m/s.
  Trajectory t = testing::FlybyPlan();
  for (auto& s : t.samples) s.time_s *= 0.5;
  const Mission m = BuildMission(t, MissionBuildOptions{});
  const auto v = ValidateMission(m, Format::kDjiWpml, *FindDroneProfile("dji-m30"), 0);
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v[0].waypoint, 0);
  EXPECT_NE(v[0].message.find("waypoint 0"), std::string::npos) << v[0].message;
  EXPECT_NE(v[0].message.find("15 m/s"), std::string::npos) << v[0].message;
}

TEST(Validation, MsdkWaypointCountGimbalAndFence) {
  MissionBuildOptions fine;
  fine.selection.max_deviation_m = 0.001;
  fine.selection.max_angle_deg = 0.01;
  Mission m = BuildMission(testing::OrbitPlan(), fine);
  ASSERT_GT(m.waypoints.size(), 99u);
  bool count = false;
  for (const auto& v : ValidateMission(m, Format::kDjiMsdkJson, *FindDroneProfile("dji-m30"), 0)) {
    count |= v.waypoint == -1 && v.limit.find("max waypoints") != std::string::npos;
  }
  EXPECT_TRUE(count);
  Mission up = BuildMission(testing::ChasePlan(), MissionBuildOptions{});  // gimbal pitch reaches −8°…−8+
  up.waypoints[2].gimbal_pitch_deg = 10;
  bool pitch = false;
  for (const auto& v : ValidateMission(up, Format::kDjiMsdkJson, *FindDroneProfile("dji-m30"), 0)) {
    pitch |= v.waypoint == 2 && v.limit == "gimbal pitch range";
  }
  EXPECT_TRUE(pitch);
  up.fence_max_up_m = 9;
  bool fence = false;
  for (const auto& v : ValidateMission(up, Format::kQgcPlan, *FindDroneProfile("px4-multirotor"), 10)) {
    fence |= v.limit == "drone altitude band";
  }
  EXPECT_TRUE(fence);
}

TEST(Validation, MavlinkItemCountAgainstProfile) {
  const Mission m = BuildMission(testing::OrbitPlan(), MissionBuildOptions{});
  EXPECT_FALSE(ValidateMission(m, Format::kQgcWpl, *FindDroneProfile("ardupilot-copter"), 800).empty());
  EXPECT_TRUE(ValidateMission(m, Format::kQgcWpl, *FindDroneProfile("px4-multirotor"), 800).empty());
}

}  // namespace
}  // namespace cinepath::exporter
