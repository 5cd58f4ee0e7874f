#include "export/msdk_spacing.h"

#include <gtest/gtest.h>

namespace cinepath::exporter {
namespace {

MissionWaypoint At(double x, double t) {
  MissionWaypoint w;
  w.position_enu_m = Eigen::Vector3d(x, 0, 10);
  w.time_s = t;
  return w;
}

TEST(MsdkSpacing, MergesCloseWaypointsIntoHolds) {
  Mission m;
  m.waypoints = {At(0, 0), At(5, 1), At(5.2, 3), At(10, 4), At(10.3, 5)};
  m.waypoints.front().record_start = true;
  m.waypoints.back().record_stop = true;
  std::vector<std::string> notes;
  const Mission out = MergeCloseWaypoints(m, 0.5, notes);
  ASSERT_EQ(out.waypoints.size(), 3u);
  EXPECT_EQ(out.waypoints[1].position_enu_m.x(), 5);
  EXPECT_EQ(out.waypoints[1].hold_s, 2.0);              // holds at x = 5 until t = 3
  EXPECT_NEAR(out.waypoints[1].speed_mps, 5.0, 1e-12);  // then 5 m in 1 s
  EXPECT_EQ(out.waypoints[2].position_enu_m.x(), 10);
  EXPECT_TRUE(out.waypoints[2].record_stop);  // the stop of the merged last waypoint survives
  EXPECT_EQ(out.waypoints[2].hold_s, 1.0);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("2 waypoint(s)"), std::string::npos) << notes[0];
  for (size_t i = 0; i + 1 < out.waypoints.size(); ++i) {
    EXPECT_GE((out.waypoints[i + 1].position_enu_m - out.waypoints[i].position_enu_m).norm(), 0.5);
  }
}

TEST(MsdkSpacing, NothingToMerge) {
  Mission m;
  m.waypoints = {At(0, 0), At(5, 1), At(10, 2)};
  std::vector<std::string> notes;
  EXPECT_EQ(MergeCloseWaypoints(m, 0.5, notes).waypoints.size(), 3u);
  EXPECT_TRUE(notes.empty());
}

}  // namespace
}  // namespace cinepath::exporter
