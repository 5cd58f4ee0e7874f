#include "export/mavlink_mission.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "export/mission_builder.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

int Count(const MavMission& m, int command) {
  int n = 0;
  for (const auto& i : m.items) n += i.command == command;
  return n;
}

Mission ChaseMission() { return BuildMission(testing::ChasePlan(), MissionBuildOptions{}); }

TEST(MavlinkMission, Px4UsesParam4YawAndFocalLength) {
  const Mission mission = ChaseMission();
  const MavMission m = BuildMavMission(mission, Firmware::kPx4, AltitudeRef::kRelative);
  EXPECT_EQ(Count(m, mav::kNavWaypoint), static_cast<int>(mission.waypoints.size()));
  EXPECT_EQ(Count(m, mav::kConditionYaw), 0);        // PX4 rejects it
  EXPECT_EQ(Count(m, mav::kDoDigicamConfigure), 0);  // PX4 rejects it
  EXPECT_GT(Count(m, mav::kSetCameraZoom), 1);       // the chase zooms
  for (const auto& item : m.items) {
    for (double p : item.params) EXPECT_TRUE(std::isfinite(p));
    if (item.command == mav::kNavWaypoint) {
      EXPECT_EQ(item.frame, mav::kFrameGlobalRelativeAlt);
      EXPECT_NEAR(item.params[3], mission.waypoints[item.waypoint].heading_deg, 1e-9);
    } else if (item.command == mav::kSetCameraZoom) {
      EXPECT_EQ(item.params[0], mav::kZoomTypeFocalLength);
      EXPECT_NEAR(item.params[1], mission.waypoints[item.waypoint].focal_length_mm, 1e-9);
    } else if (item.command != mav::kNavTakeoff) {
      EXPECT_EQ(item.frame, mav::kFrameMission);
    }
  }
  EXPECT_EQ(m.items.front().command, mav::kNavTakeoff);
  EXPECT_EQ(m.items.back().command, mav::kNavReturnToLaunch);
  ASSERT_FALSE(m.notes.empty());
  EXPECT_NE(m.notes[0].find("aperture"), std::string::npos);
}

TEST(MavlinkMission, ArduPilotUsesConditionYawPercentZoomAndAperture) {
  const Mission mission = ChaseMission();
  const MavMission m = BuildMavMission(mission, Firmware::kArduPilot, AltitudeRef::kAmsl);
  EXPECT_EQ(Count(m, mav::kConditionYaw), static_cast<int>(mission.waypoints.size()));
  EXPECT_EQ(Count(m, mav::kSetCameraFocus), 0);  // no metres on ArduPilot
  EXPECT_GT(Count(m, mav::kDoDigicamConfigure), 1);
  for (const auto& item : m.items) {
    if (item.command == mav::kNavWaypoint) {
      EXPECT_EQ(item.frame, mav::kFrameGlobal);
      EXPECT_NEAR(item.params[6], mission.waypoints[item.waypoint].amsl_m, 1e-9);
      EXPECT_EQ(item.params[3], 0);  // ignored by Copter: never NaN
    }
    if (item.command == mav::kSetCameraZoom) {
      EXPECT_EQ(item.params[0], mav::kZoomTypeRange);
      const double f = mission.waypoints[item.waypoint].focal_length_mm;
      EXPECT_NEAR(item.params[1], (f - 24) / (70 - 24) * 100, 1e-9);
    }
    if (item.command == mav::kDoGimbalManagerPitchYaw) {
      EXPECT_TRUE(std::isfinite(item.params[0]) && std::isfinite(item.params[1]));  // both angles
    }
  }
  bool focus_note = false;
  for (const auto& n : m.notes) focus_note |= n.find("focus") != std::string::npos;
  EXPECT_TRUE(focus_note);
}

TEST(MavlinkMission, FocusAtInfinityOnPx4) {
  const Mission mission = BuildMission(testing::FlybyPlan(), MissionBuildOptions{});
  const MavMission m = BuildMavMission(mission, Firmware::kPx4, AltitudeRef::kRelative);
  const MavItem* last_focus = nullptr;
  for (const auto& item : m.items) {
    if (item.command == mav::kSetCameraFocus) last_focus = &item;
  }
  ASSERT_NE(last_focus, nullptr);
  EXPECT_EQ(last_focus->params[0], mav::kFocusTypeRange);
  EXPECT_EQ(last_focus->params[1], 100);
}

TEST(MavlinkMission, RecordingFollowsEachFirmwaresDoItemTiming) {
  Mission mission = ChaseMission();
  ASSERT_GE(mission.waypoints.size(), 4u);
  mission.waypoints[1].record_stop = mission.waypoints[1].transit_after = true;  // a cut after waypoint 1
  mission.waypoints[2].record_start = true;
  auto sequence = [](const MavMission& m) {
    std::vector<std::pair<int, int>> out;  // (command, waypoint) of NAV_WAYPOINT and video items
    for (const auto& i : m.items) {
      if (i.command == mav::kNavWaypoint || i.command == mav::kVideoStartCapture ||
          i.command == mav::kVideoStopCapture) {
        out.emplace_back(i.command, i.command == mav::kNavWaypoint ? i.waypoint : -1);
      }
    }
    return out;
  };
  const auto px4 = sequence(BuildMavMission(mission, Firmware::kPx4, AltitudeRef::kRelative));
  // PX4: NAV0 START NAV1 STOP NAV2 START NAV3 ... STOP
  ASSERT_GE(px4.size(), 7u);
  EXPECT_EQ(px4[0], std::make_pair(mav::kNavWaypoint, 0));
  EXPECT_EQ(px4[1].first, mav::kVideoStartCapture);
  EXPECT_EQ(px4[2], std::make_pair(mav::kNavWaypoint, 1));
  EXPECT_EQ(px4[3].first, mav::kVideoStopCapture);
  EXPECT_EQ(px4[4], std::make_pair(mav::kNavWaypoint, 2));
  EXPECT_EQ(px4[5].first, mav::kVideoStartCapture);
  EXPECT_EQ(px4.back().first, mav::kVideoStopCapture);
  const MavMission ap_items = BuildMavMission(mission, Firmware::kArduPilot, AltitudeRef::kRelative);
  const auto ap = sequence(ap_items);
  // ArduPilot: NAV0 NAV1 START(of 0) NAV2 STOP(of 1) NAV3 START(of 2) ... RTL STOP
  EXPECT_EQ(ap[0], std::make_pair(mav::kNavWaypoint, 0));
  EXPECT_EQ(ap[1], std::make_pair(mav::kNavWaypoint, 1));
  EXPECT_EQ(ap[2].first, mav::kVideoStartCapture);
  EXPECT_EQ(ap[3], std::make_pair(mav::kNavWaypoint, 2));
  EXPECT_EQ(ap[4].first, mav::kVideoStopCapture);
  EXPECT_EQ(ap[5], std::make_pair(mav::kNavWaypoint, 3));
  EXPECT_EQ(ap[6].first, mav::kVideoStartCapture);
  EXPECT_EQ(ap_items.items.back().command, mav::kVideoStopCapture);
  EXPECT_EQ(ap_items.items[ap_items.items.size() - 2].command, mav::kNavReturnToLaunch);
}

TEST(MavlinkMission, NoEllipsoidalFrame) {
  EXPECT_THROW(BuildMavMission(ChaseMission(), Firmware::kPx4, AltitudeRef::kEllipsoid), InputError);
}

}  // namespace
}  // namespace cinepath::exporter
