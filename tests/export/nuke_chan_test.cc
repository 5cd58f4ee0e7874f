#include "export/nuke_chan.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// Ry(ry) Rx(rx) Rz(rz): Nuke's ZXY order, built from the axes (independent of ZxyEulerDeg's formulas).
Eigen::Quaterniond FromZxy(double rx_deg, double ry_deg, double rz_deg) {
  return Eigen::AngleAxisd(ry_deg * kRadPerDeg, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(rx_deg * kRadPerDeg, Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(rz_deg * kRadPerDeg, Eigen::Vector3d::UnitZ());
}

TEST(NukeChan, ZxyEulerAnglesRebuildTheRotation) {
  for (double rx : {-89.0, -45.0, -10.0, 0.0, 30.0, 89.5}) {
    for (double ry : {-170.0, -60.0, 0.0, 45.0, 179.0}) {
      for (double rz : {-120.0, -5.0, 0.0, 20.0, 175.0}) {
        const Eigen::Vector3d e = ZxyEulerDeg(FromZxy(rx, ry, rz));
        EXPECT_NEAR(e(0), rx, 1e-9);
        EXPECT_NEAR(e(1), ry, 1e-9);
        EXPECT_NEAR(e(2), rz, 1e-9);
      }
    }
  }
}

TEST(NukeChan, StraightDownKeepsTheRollAndGivesTheSameRotation) {
  // Looking straight down (rx = -90) only ry + rz is defined: rz stays the previous key's.
  const Eigen::Quaterniond q = FromZxy(-90, 40, 0);
  const Eigen::Vector3d previous(-89, 10, 15);
  const Eigen::Vector3d e = ZxyEulerDeg(q, &previous);
  EXPECT_DOUBLE_EQ(e(0), -90);
  EXPECT_NEAR(e(2), 15, 1e-9);
  EXPECT_LT(FromZxy(e(0), e(1), e(2)).angularDistance(q), 1e-9);
}

TEST(NukeChan, AnglesStayContinuousAcrossAFullTurn) {
  // A pan past 180 degrees goes on to 190, not back to -170.
  const Eigen::Vector3d previous(0, 179, 0);
  EXPECT_NEAR(ZxyEulerDeg(FromZxy(0, 190, 0), &previous)(1), 190, 1e-9);
}

TEST(NukeChan, OneLinePerSampleInYUpMetres) {
  const Trajectory plan = testing::OrbitPlan(1, 10);
  const CameraTrack track = TrackOfFlight(plan, "north", "plan.json", false);
  std::istringstream in(WriteNukeChan(track));
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    double frame, tx, ty, tz, rx, ry, rz, vfov;
    ASSERT_TRUE(fields >> frame >> tx >> ty >> tz >> rx >> ry >> rz >> vfov) << line;
    const TrajectorySample& s = plan.samples[n];
    EXPECT_EQ(frame, n);
    // x east, y up, z south
    EXPECT_NEAR(tx, s.position_enu_m.x(), 1e-6);
    EXPECT_NEAR(ty, s.position_enu_m.z(), 1e-6);
    EXPECT_NEAR(tz, -s.position_enu_m.y(), 1e-6);
    // the camera's -Z is the plan's optical axis
    const Eigen::Vector3d forward_yup = FromZxy(rx, ry, rz) * Eigen::Vector3d(0, 0, -1);
    const Eigen::Vector3d forward_enu = s.world_from_camera * Eigen::Vector3d::UnitZ();
    EXPECT_LT((forward_yup - Eigen::Vector3d(forward_enu.x(), forward_enu.z(), -forward_enu.y())).norm(), 1e-6);
    EXPECT_GT(vfov, 0);
    ++n;
  }
  EXPECT_EQ(n, static_cast<int>(plan.samples.size()));
}

}  // namespace
}  // namespace cinepath::exporter
