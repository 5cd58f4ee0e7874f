#include "core/feasibility.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/drone_profiles.h"

namespace cinepath {
namespace {

// A straight climb at a constant rate, sampled at 10 Hz.
Trajectory Climb(double rate_m_s, size_t n) {
  Trajectory plan;
  plan.frame_rate_hz = 10;
  plan.drone = DefaultDroneProfile();
  plan.camera.min_focal_length_mm = 24;
  plan.camera.max_focal_length_mm = 24;
  for (size_t i = 0; i < n; ++i) {
    TrajectorySample s;
    s.time_s = i / 10.0;
    s.position_enu_m = Eigen::Vector3d(0, 0, 10 + rate_m_s * s.time_s);
    s.focal_length_mm = 24;
    s.f_number = 4;
    s.focus_distance_m = 10;
    s.shot = i < n / 2 ? "a" : "b";
    plan.samples.push_back(s);
  }
  return plan;
}

// Which limits are minima, as the messages and the previs page write them ("worst < limit").
TEST(Feasibility, MinimaAreKnownByName) {
  for (const char* limit : {"altitude_min", "subject_distance", "terrain_clearance", "focal_length_min",
                            "focus_distance_min", "f_number_min", "gimbal_pitch_min"}) {
    EXPECT_TRUE(IsMinimumLimit(limit)) << limit;
  }
  for (const char* limit : {"altitude_max", "jerk", "horizontal_speed", "yaw_rate", "focus_rate", "no_such_limit"}) {
    EXPECT_FALSE(IsMinimumLimit(limit)) << limit;
  }
}

TEST(Feasibility, ClimbRateRangesSplitByShot) {
  const Trajectory plan = Climb(4.0, 21);  // PX4 climb limit 3 m/s
  const auto report = CheckFeasibility(plan, std::vector<bool>(21, false), {});
  ASSERT_EQ(report.violations.size(), 2u);
  EXPECT_EQ(report.violations[0].limit, "climb_rate");
  EXPECT_EQ(report.violations[0].shot, "a");
  EXPECT_NEAR(report.violations[0].start_time_s, 0.0, 1e-12);
  EXPECT_NEAR(report.violations[0].end_time_s, 0.9, 1e-12);
  EXPECT_NEAR(report.violations[0].worst_value, 4.0, 1e-9);
  EXPECT_EQ(report.violations[1].shot, "b");
  EXPECT_NEAR(report.violations[1].end_time_s, 2.0, 1e-12);
  EXPECT_TRUE(CheckFeasibility(Climb(2.9, 21), std::vector<bool>(21, false), {}).feasible());
}

TEST(Feasibility, EveryLimitSampleBySample) {
  // From sample 5 to 10 it climbs at 4 m/s (over the 3 m/s limit), else at 1 m/s; a cut before sample 15.
  Trajectory plan = Climb(1.0, 20);
  for (size_t i = 5; i < 20; ++i) plan.samples[i].position_enu_m.z() += 0.3 * (std::min<size_t>(i, 10) - 5);
  std::vector<bool> cut(20, false);
  cut[15] = true;
  const std::vector<LimitSeries> series = MeasureLimits(plan, cut, {});
  const auto climb = std::find_if(series.begin(), series.end(), [](const auto& s) { return s.limit == "climb_rate"; });
  ASSERT_NE(climb, series.end());
  ASSERT_EQ(climb->values.size(), 20u);
  for (size_t i = 0; i < 20; ++i) {
    // Central differences: samples 6-9 see the fast climb on both sides, 5 and 10 on one side.
    const double expected = i >= 6 && i <= 9 ? 4.0 : (i == 5 || i == 10 ? 2.5 : 1.0);
    EXPECT_NEAR(climb->values[i], expected, 1e-9) << i;
    EXPECT_NEAR(climb->Excess(i), std::max(0.0, expected - 3.0), 1e-9) << i;
  }
  // The terrain is not measured without a mesh: NaN, never broken.
  const auto terrain =
      std::find_if(series.begin(), series.end(), [](const auto& s) { return s.limit == "terrain_clearance"; });
  ASSERT_NE(terrain, series.end());
  EXPECT_TRUE(std::isnan(terrain->values[3]));
  EXPECT_EQ(terrain->Excess(3), 0.0);
  // The report is the series merged into ranges.
  const auto ranges = ViolationsOf(*climb, plan);
  ASSERT_EQ(ranges.size(), 1u);
  EXPECT_NEAR(ranges[0].start_time_s, 0.6, 1e-12);
  EXPECT_NEAR(ranges[0].end_time_s, 0.9, 1e-12);
  int climbs = 0;
  for (const auto& v : CheckFeasibility(plan, cut, {}).violations) {
    if (v.limit != "climb_rate") continue;
    ++climbs;
    EXPECT_EQ(v.start_time_s, ranges[0].start_time_s);
    EXPECT_EQ(v.end_time_s, ranges[0].end_time_s);
    EXPECT_EQ(v.worst_value, ranges[0].worst_value);
  }
  EXPECT_EQ(climbs, 1);
}

TEST(Feasibility, NothingIsDifferentiatedAcrossACut) {
  Trajectory plan = Climb(1.0, 20);
  for (size_t i = 10; i < 20; ++i) plan.samples[i].position_enu_m.x() += 500;  // a jump
  std::vector<bool> cut(20, false);
  EXPECT_FALSE(CheckFeasibility(plan, cut, {}).feasible());
  cut[10] = true;
  EXPECT_TRUE(CheckFeasibility(plan, cut, {}).feasible());
}

TEST(Feasibility, AltitudeAndLensRequests) {
  Trajectory plan = Climb(0.0, 5);
  plan.samples[2].position_enu_m.z() = 0.5;  // below the 1 m floor
  std::vector<LensRequest> requests(5, LensRequest{24, 10, 4});
  requests[3].focal_length_mm = 30;  // the framing wanted more than the lens has
  const auto report = CheckFeasibility(plan, std::vector<bool>(5, false), requests);
  bool altitude = false, focal = false;
  for (const auto& v : report.violations) {
    altitude = altitude || (v.limit == "altitude_min" && v.worst_value == 0.5);
    focal = focal || (v.limit == "focal_length_max" && v.worst_value == 30);
  }
  EXPECT_TRUE(altitude);
  EXPECT_TRUE(focal);
}

}  // namespace
}  // namespace cinepath
