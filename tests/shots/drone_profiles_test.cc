// The shipped drone profiles carry the figures their sources give (shots/drone_profiles.cc cites
// them); a changed figure must be a deliberate edit of both.
#include "shots/drone_profiles.h"

#include <gtest/gtest.h>

namespace cinepath {
namespace {

TEST(DroneProfiles, Px4DefaultQuadFigures) {
  const DroneLimits d = Px4DefaultQuadLimits();
  EXPECT_EQ(d.name, "px4_default_quad");
  EXPECT_EQ(d.max_horizontal_speed_m_s, 12);  // MPC_XY_VEL_MAX
  EXPECT_EQ(d.max_climb_rate_m_s, 3);
  EXPECT_EQ(d.max_descent_rate_m_s, 1.5);
  EXPECT_EQ(d.max_altitude_m, 120);  // EU 2019/947 open category
  EXPECT_EQ(d.min_gimbal_pitch_deg, -90);
}

TEST(DroneProfiles, DjiClassFiguresFromDjiSources) {
  const DroneLimits d = DjiClassLimits();
  EXPECT_EQ(d.name, "dji_class");
  EXPECT_EQ(d.max_horizontal_speed_m_s, 15);      // missions.md: DJI mission speeds <= 15 m/s
  EXPECT_EQ(d.max_climb_rate_m_s, 5);             // MSDK v4 VERTICAL_CONTROL_MAX_VELOCITY
  EXPECT_EQ(d.max_descent_rate_m_s, 4);           // MSDK v4 VERTICAL_CONTROL_MIN_VELOCITY = -4
  EXPECT_EQ(d.max_yaw_rate_deg_s, 100);           // MSDK v4 yaw angular velocity limit
  EXPECT_EQ(d.max_gimbal_pitch_rate_deg_s, 120);  // DJIGimbalSpeedRotation [0, 120] deg/s
  EXPECT_EQ(d.min_gimbal_pitch_deg, -90);
  EXPECT_EQ(d.max_gimbal_pitch_deg, 0);
  EXPECT_EQ(d.max_altitude_m, 500);  // MSDK v4 waypoint altitude
}

TEST(DroneProfiles, LookupByName) {
  for (const auto name : DroneProfileNames()) {
    const auto found = FindDroneProfile(name);
    ASSERT_TRUE(found.has_value()) << name;
    EXPECT_EQ(found->name, name);
  }
  EXPECT_FALSE(FindDroneProfile("no_such_drone").has_value());
  // Every limit is a positive magnitude and the bands are ordered.
  for (const auto name : DroneProfileNames()) {
    const DroneLimits d = *FindDroneProfile(name);
    EXPECT_GT(d.max_horizontal_speed_m_s, 0);
    EXPECT_GT(d.max_climb_rate_m_s, 0);
    EXPECT_GT(d.max_descent_rate_m_s, 0);
    EXPECT_GT(d.max_yaw_rate_deg_s, 0);
    EXPECT_GT(d.max_gimbal_pitch_rate_deg_s, 0);
    EXPECT_LT(d.min_gimbal_pitch_deg, d.max_gimbal_pitch_deg);
    EXPECT_LT(d.min_altitude_m, d.max_altitude_m);
  }
}

}  // namespace
}  // namespace cinepath
