#include "export/dji_turns.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/angles.h"

namespace cinepath::exporter {
namespace {

// An L-shaped plan: 10 m east to the corner at the origin, then 10 m north; a sample every 0.5 m.
std::vector<TrajectorySample> SharpCorner() {
  std::vector<TrajectorySample> samples;
  for (int i = 0; i <= 40; ++i) {
    TrajectorySample s;
    s.time_s = i * 0.1;
    s.position_enu_m = i <= 20 ? Eigen::Vector3d(-10 + 0.5 * i, 0, 20) : Eigen::Vector3d(0, 0.5 * (i - 20), 20);
    samples.push_back(s);
  }
  return samples;
}

TEST(DjiTurns, ArcOfAQuarterTurnPassesDTanDeltaOver4FromTheCorner) {
  // Hand computation: turn angle δ = 90°, damping d = 2 m → radius r = d / tan(45°) = 2 m, centre at
  // (−2, 2), the arc passes |PC| − r = 2√2 − 2 = 2·tan(22.5°) = 0.828427 m from the corner.
  const std::vector<Eigen::Vector3d> corners = {{-10, 0, 20}, {0, 0, 20}, {0, 10, 20}};
  const std::vector<double> damping = {0, 2, 0};
  const double expected = 2 * std::tan(RadFromDeg(22.5));
  EXPECT_NEAR(expected, 2 * std::sqrt(2.0) - 2, 1e-12);
  EXPECT_NEAR(DistanceToTurnPath(corners, damping, 0, corners[1]), expected, 1e-9);
  EXPECT_NEAR(DistanceToTurnPath(corners, damping, 1, corners[1]), expected, 1e-9);
  // The turn starts 2 m before the corner: a point on the leg 3 m before it lies on the path.
  EXPECT_NEAR(DistanceToTurnPath(corners, damping, 0, Eigen::Vector3d(-3, 0, 20)), 0, 1e-12);
  // The arc's end points are on the legs, and a point on the arc is at the radius from the centre.
  EXPECT_NEAR(
      DistanceToTurnPath(corners, damping, 0,
                         Eigen::Vector3d(-2 + 2 * std::cos(RadFromDeg(-30)), 2 + 2 * std::sin(RadFromDeg(-30)), 20)),
      0, 2 * (1 - std::cos(kPi / 2 / 32 / 2)) + 1e-12);
  // Without damping the path is the corner itself.
  EXPECT_NEAR(DistanceToTurnPath(corners, {0, 0, 0}, 0, corners[1]), 0, 1e-12);
}

TEST(DjiTurns, FitChoosesTheLargestDampingWithinTolerance) {
  const auto samples = SharpCorner();
  // Tolerance 0.5 m: d·tan(22.5°) ≤ 0.5 ⇒ d ≤ 1.2071. Candidates 0.45·10 = 4.5 m × 0.7^k:
  // 4.5, 3.15, 2.205, 1.5435, 1.08045 → 1.08 m (written to the centimetre) → 0.447351 m.
  const TurnFit fit = FitCoordinatedTurns(samples, {0, 20, 40}, {true, false, true}, 0.5);
  ASSERT_EQ(fit.damping_m.size(), 3u);
  EXPECT_EQ(fit.damping_m[0], 0);
  EXPECT_DOUBLE_EQ(fit.damping_m[1], 1.08);
  EXPECT_EQ(fit.damping_m[2], 0);
  EXPECT_NEAR(fit.max_deviation_m, 1.08 * std::tan(RadFromDeg(22.5)), 1e-9);
  // A tolerance no damping distance meets: the aircraft stops at the corner, the path is the L.
  const TurnFit tight = FitCoordinatedTurns(samples, {0, 20, 40}, {true, false, true}, 0.05);
  EXPECT_EQ(tight.damping_m[1], 0);
  EXPECT_NEAR(tight.max_deviation_m, 0, 1e-12);
  // A forced stop is honoured.
  EXPECT_EQ(FitCoordinatedTurns(samples, {0, 20, 40}, {true, true, true}, 0.5).damping_m[1], 0);
}

TEST(DjiTurns, DampingOnASegmentSumsToLessThanItsLength) {
  // A zig-zag of 4 m legs with gentle turns: every corner may turn, the two damping distances on a
  // leg must still sum to less than the leg (docs/mission-formats.md §4.1).
  std::vector<TrajectorySample> samples;
  std::vector<int> waypoints;
  Eigen::Vector3d p(0, 0, 10);
  for (int leg = 0; leg < 6; ++leg) {
    const Eigen::Vector3d dir(std::cos(leg % 2 ? 0.2 : -0.2), std::sin(leg % 2 ? 0.2 : -0.2), 0);
    for (int k = 0; k < 8; ++k) {
      if (k == 0) waypoints.push_back(static_cast<int>(samples.size()));
      TrajectorySample s;
      s.position_enu_m = p + dir * (0.5 * k);
      samples.push_back(s);
    }
    p += dir * 4;
  }
  TrajectorySample last;
  last.position_enu_m = p;
  waypoints.push_back(static_cast<int>(samples.size()));
  samples.push_back(last);
  std::vector<bool> stop(waypoints.size(), false);
  stop.front() = stop.back() = true;
  const TurnFit fit = FitCoordinatedTurns(samples, waypoints, stop, 1.0);
  for (size_t w = 0; w + 1 < waypoints.size(); ++w) {
    const double length = (samples[waypoints[w + 1]].position_enu_m - samples[waypoints[w]].position_enu_m).norm();
    EXPECT_LT(fit.damping_m[w] + fit.damping_m[w + 1], length);
    if (w > 0) EXPECT_GT(fit.damping_m[w], 0);  // gentle turns at a loose tolerance: all turn
  }
  EXPECT_LE(fit.max_deviation_m, 1.0);
}

}  // namespace
}  // namespace cinepath::exporter
