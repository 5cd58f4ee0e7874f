#include "export/waypoint_selection.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

// Brute-force check of the promise: every sample between two chosen waypoints is within tolerance.
void ExpectWithinTolerance(const std::vector<TrajectorySample>& samples, const Selection& sel,
                           const SelectionOptions& opt) {
  double worst_dev = 0, worst_angle = 0;
  for (size_t i = 0; i + 1 < sel.sample_indices.size(); ++i) {
    const LegError e = MeasureLeg(samples, sel.sample_indices[i], sel.sample_indices[i + 1]);
    EXPECT_LE(e.deviation_m, opt.max_deviation_m + 1e-12);
    EXPECT_LE(e.angle_deg, opt.max_angle_deg + 1e-12);
    worst_dev = std::max(worst_dev, e.deviation_m);
    worst_angle = std::max(worst_angle, e.angle_deg);
  }
  EXPECT_DOUBLE_EQ(sel.max_deviation_m, worst_dev);
  EXPECT_DOUBLE_EQ(sel.max_angle_error_deg, worst_angle);
}

TEST(WaypointSelection, StraightConstantLineNeedsTwoWaypoints) {
  Trajectory t = testing::EmptyPlan("s", "FLYBY", 5, 10);
  for (int i = 0; i <= 50; ++i) testing::AddSample(t, i / 10.0, Eigen::Vector3d(i * 0.5, 0, 10), 90, -10, 24, 10, 4);
  const Selection sel = SelectWaypoints(t.samples, {0.1, 1.0});
  EXPECT_EQ(sel.sample_indices, (std::vector<int>{0, 50}));
  EXPECT_NEAR(sel.max_deviation_m, 0, 1e-9);
}

TEST(WaypointSelection, OrbitStaysWithinToleranceAndTighterMeansMore) {
  const Trajectory t = testing::OrbitPlan();
  size_t previous = 0;
  for (double tol : {2.0, 0.5, 0.1, 0.02}) {
    const SelectionOptions opt{tol, 30.0};
    const Selection sel = SelectWaypoints(t.samples, opt);
    ExpectWithinTolerance(t.samples, sel, opt);
    EXPECT_EQ(sel.sample_indices.front(), 0);
    EXPECT_EQ(sel.sample_indices.back(), static_cast<int>(t.samples.size()) - 1);
    EXPECT_GT(sel.sample_indices.size(), previous) << "tolerance " << tol;
    previous = sel.sample_indices.size();
  }
  // Sagitta of a chord: deviation 0.5 m on r = 30 m allows chords of 2*sqrt(2*30*0.5) ≈ 10.9 m;
  // half a turn is 94 m, so at least 9 legs are needed.
  const Selection half_metre = SelectWaypoints(t.samples, {0.5, 30.0});
  EXPECT_GE(half_metre.sample_indices.size(), 10u);
  EXPECT_LE(half_metre.sample_indices.size(), 14u);
}

TEST(WaypointSelection, PanWhileHoveringSplitsOnAngle) {
  Trajectory t = testing::EmptyPlan("pan", "PAN", 4, 10);
  for (int i = 0; i <= 40; ++i) testing::AddSample(t, i / 10.0, Eigen::Vector3d(0, 0, 10), i * 2.0, -5, 24, 10, 4);
  // Heading changes linearly in time but the leg has zero length: time interpolation is exact.
  const Selection linear = SelectWaypoints(t.samples, {0.1, 1.0});
  EXPECT_EQ(linear.sample_indices.size(), 2u);
  // An ease-in pan is not linear in time: it needs more waypoints.
  Trajectory eased = testing::EmptyPlan("pan", "PAN", 4, 10);
  for (int i = 0; i <= 40; ++i) {
    const double u = i / 40.0;
    testing::AddSample(eased, i / 10.0, Eigen::Vector3d(0, 0, 10), 80 * u * u, -5, 24, 10, 4);
  }
  const SelectionOptions opt{0.1, 1.0};
  const Selection sel = SelectWaypoints(eased.samples, opt);
  ExpectWithinTolerance(eased.samples, sel, opt);
  EXPECT_GT(sel.sample_indices.size(), 3u);
}

TEST(WaypointSelection, HeadingWrapsTheShortWay) {
  Trajectory t = testing::EmptyPlan("wrap", "PAN", 2, 10);
  for (int i = 0; i <= 20; ++i) {
    testing::AddSample(t, i / 10.0, Eigen::Vector3d(i, 0, 10), 350 + i, -5, 24, 10, 4);  // 350 → 10 through north
  }
  const Selection sel = SelectWaypoints(t.samples, {0.1, 0.5});
  EXPECT_EQ(sel.sample_indices.size(), 2u);
  EXPECT_LT(sel.max_angle_error_deg, 1e-9);
}

TEST(WaypointSelection, RejectsBadTolerances) {
  const Trajectory t = testing::OrbitPlan();
  EXPECT_THROW(SelectWaypoints(t.samples, {0.0, 1.0}), InputError);
  EXPECT_THROW(SelectWaypoints(t.samples, {1.0, -1.0}), InputError);
  EXPECT_THROW(SelectWaypoints(t.samples, {NAN, 1.0}), InputError);
}

}  // namespace
}  // namespace cinepath::exporter
