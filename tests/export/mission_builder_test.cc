#include "export/mission_builder.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/geoid.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

TEST(MissionBuilder, AltitudesInEveryReference) {
  const Trajectory t = testing::OrbitPlan();
  MissionBuildOptions opt;
  const Mission m = BuildMission(t, opt);
  ASSERT_GE(m.waypoints.size(), 2u);
  const double n_home = Egm96Geoid::Default().UndulationM(m.home.lat_deg, m.home.lon_deg);
  EXPECT_NEAR(m.home.ellipsoidal_height_m - m.home.amsl_m, n_home, 1e-9);
  EXPECT_NEAR(n_home, 47.34, 0.05);  // docs/mission-formats.md §5: N(47.3977, 8.5456) ≈ 47.335 m
  for (const auto& wp : m.waypoints) {
    const double n = Egm96Geoid::Default().UndulationM(wp.lat_deg, wp.lon_deg);
    EXPECT_NEAR(wp.ellipsoidal_height_m - wp.amsl_m, n, 1e-9);
    EXPECT_NEAR(wp.relative_alt_m, wp.amsl_m - m.home.amsl_m, 1e-9);
    // Within 30 m of the origin the relative altitude is the ENU up coordinate to ~1 mm
    // (earth curvature over 30 m ≈ 0.07 mm; geoid slope is tiny).
    EXPECT_NEAR(wp.relative_alt_m, wp.position_enu_m.z(), 5e-3);
  }
  // Orbit at constant speed: pi*30 m in 10 s.
  EXPECT_NEAR(m.waypoints.front().speed_mps, 3.0 * kPi * 0.99, 0.1);
}

TEST(MissionBuilder, HomeOptionShiftsRelativeAltitudes) {
  const Trajectory t = testing::ChasePlan();
  MissionBuildOptions opt;
  const Mission base = BuildMission(t, opt);
  opt.home = HomeSpec{47.3977419, 8.545594, base.home.amsl_m - 10};
  const Mission shifted = BuildMission(t, opt);
  EXPECT_NEAR(shifted.waypoints[3].relative_alt_m, base.waypoints[3].relative_alt_m + 10, 1e-9);
}

TEST(MissionBuilder, BadInput) {
  Trajectory t = testing::OrbitPlan();
  t.samples[7].gimbal_pitch_deg = NAN;
  try {
    BuildMission(t, MissionBuildOptions{});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("samples[7].gimbal_pitch_deg"), std::string::npos) << e.what();
  }
  Trajectory no_origin = testing::OrbitPlan();
  no_origin.origin.reset();
  EXPECT_THROW(BuildMission(no_origin, MissionBuildOptions{}), InputError);
  MissionBuildOptions absolute;
  absolute.absolute_altitudes = true;
  absolute.home = HomeSpec{47.39, 8.54, 400};
  EXPECT_THROW(BuildMission(no_origin, absolute), InputError);
  MissionBuildOptions relative_home;
  relative_home.home = HomeSpec{47.39, 8.54, 400};
  const Mission m = BuildMission(no_origin, relative_home);
  EXPECT_NEAR(m.origin.lat_deg, 47.39, 1e-12);
  EXPECT_NEAR(m.waypoints.front().relative_alt_m, 25, 5e-3);
}

// A plan without an origin measures its angles against its own axes; once a scene's origin places it
// (here 1 km off the pole), each waypoint's heading and pitch are taken against true north and the
// vertical where it flies: the orbit's subject stays dead ahead of every waypoint.
TEST(MissionBuilder, APlanPlacedByTheScenesOriginFliesTrueHeadings) {
  Trajectory t = testing::OrbitPlan();
  t.origin.reset();
  MissionBuildOptions options;
  options.scene_origin = Geodetic{89.99, 20, 100};
  const Mission m = BuildMission(t, options);
  const EnuFrame frame(*options.scene_origin);
  ASSERT_GE(m.waypoints.size(), 3u);
  double largest_change_deg = 0;
  for (const MissionWaypoint& wp : m.waypoints) {
    const Eigen::Vector3d to_subject(-wp.position_enu_m.x(), -wp.position_enu_m.y(), 1.5 - wp.position_enu_m.z());
    const Eigen::Vector3d local = frame.LocalLevelFromEnu(wp.position_enu_m) * to_subject;
    EXPECT_NEAR(AngleDiffDeg(wp.heading_deg, HeadingDegFromEnuYaw(std::atan2(local.y(), local.x()))), 0.0, 1e-6);
    EXPECT_NEAR(wp.gimbal_pitch_deg, DegFromRad(std::atan2(local.z(), local.head<2>().norm())), 1e-6);
    const TrajectorySample& planned = t.samples[static_cast<size_t>(wp.sample_index)];
    largest_change_deg =
        std::max(largest_change_deg, std::abs(AngleDiffDeg(planned.drone_heading_deg, wp.heading_deg)));
  }
  EXPECT_GT(largest_change_deg, 0.5);  // near the pole the two norths differ
}

TEST(MissionBuilder, CutsSplitTheSelectionAndInsertATransit) {
  Trajectory t = testing::EmptyPlan("a", "DOLLY", 2, 10);
  t.shots.push_back(ShotSpan{"b", "DOLLY", 2.1, 4, "actor", "cut"});
  for (int i = 0; i <= 20; ++i) testing::AddSample(t, i / 10.0, Eigen::Vector3d(i * 0.5, 0, 10), 90, -10, 24, 10, 4);
  for (int i = 21; i <= 40; ++i) {
    testing::AddSample(t, i / 10.0, Eigen::Vector3d(100 + i * 0.5, 50, 10), 90, -10, 24, 10, 4);
    t.samples.back().shot = "b";
  }
  const Mission m = BuildMission(t, MissionBuildOptions{});
  ASSERT_EQ(m.waypoints.size(), 4u);  // two straight runs, two waypoints each
  EXPECT_EQ(m.cut_count, 1);
  EXPECT_EQ(m.waypoints[1].sample_index, 20);
  EXPECT_EQ(m.waypoints[2].sample_index, 21);
  EXPECT_TRUE(m.waypoints[0].record_start && m.waypoints[1].record_stop && m.waypoints[1].transit_after);
  EXPECT_TRUE(m.waypoints[2].record_start && m.waypoints[3].record_stop && !m.waypoints[2].transit_after);
  EXPECT_EQ(m.waypoints[1].speed_mps, 5.0);          // transit, not the 1000 m/s jump
  EXPECT_NEAR(m.waypoints[2].speed_mps, 5.0, 1e-9);  // 9.5 m in 1.9 s
  EXPECT_NEAR(m.max_deviation_reached_m, 0, 1e-9);
  // A "continuous" transition is one run.
  t.shots[1].transition = "continuous";
  EXPECT_EQ(BuildMission(t, MissionBuildOptions{}).cut_count, 0);
}

TEST(MissionBuilder, ParseHomeSpec) {
  const HomeSpec h = ParseHomeSpec("47.5,8.25,410.5", "--home");
  EXPECT_EQ(h.lat_deg, 47.5);
  EXPECT_EQ(h.lon_deg, 8.25);
  EXPECT_EQ(h.amsl_m, 410.5);
  EXPECT_THROW(ParseHomeSpec("47.5,8.25", "--home"), InputError);
  EXPECT_THROW(ParseHomeSpec("95,8,1", "--home"), InputError);
  EXPECT_THROW(ParseHomeSpec("a,b,c", "--home"), InputError);
}

}  // namespace
}  // namespace cinepath::exporter
