// The shipped drone profiles carry the figures their sources give (core/drone_profiles.cc cites them,
// docs/drones.md tabulates them); a changed figure must be a deliberate edit of all three.
#include "core/drone_profiles.h"

#include <gtest/gtest.h>

#include "tests/support/input_error.h"

#include "core/error.h"

namespace cinepath {
namespace {

TEST(DroneProfiles, Px4MultirotorFigures) {
  const DroneProfile d = *FindDroneProfile("px4-multirotor");
  EXPECT_EQ(d.firmware, "px4");
  EXPECT_EQ(d.max_horizontal_speed_m_s, 12);  // MPC_XY_VEL_MAX
  EXPECT_EQ(d.max_climb_rate_m_s, 3);         // MPC_Z_VEL_MAX_UP
  EXPECT_EQ(d.max_descent_rate_m_s, 1.5);     // MPC_Z_VEL_MAX_DN
  EXPECT_EQ(d.max_jerk_m_s3, 4);              // MPC_JERK_AUTO
  EXPECT_EQ(d.max_altitude_m, 120);           // EU 2019/947 open category
  EXPECT_EQ(d.max_mission_items, 2000);       // NUM_MISSIONS_SUPPORTED
  EXPECT_EQ(&DefaultDroneProfile(), &DroneProfiles().front());
  EXPECT_EQ(DefaultDroneProfile().name, "px4-multirotor");
}

TEST(DroneProfiles, ArduCopterDefaults) {
  const DroneProfile d = *FindDroneProfile("ardupilot-copter");
  EXPECT_EQ(d.max_horizontal_speed_m_s, 10);  // WPNAV_SPEED 1000 cm/s
  EXPECT_EQ(d.max_climb_rate_m_s, 2.5);       // WPNAV_SPEED_UP
  EXPECT_EQ(d.max_descent_rate_m_s, 1.5);     // WPNAV_SPEED_DN
  EXPECT_EQ(d.max_acceleration_m_s2, 2.5);    // WPNAV_ACCEL
  EXPECT_EQ(d.max_mission_items, 724);
}

TEST(DroneProfiles, DjiAircraftFromDjiSources) {
  const DroneProfile m30 = *FindDroneProfile("dji-m30");
  EXPECT_EQ(m30.max_horizontal_speed_m_s, 15);  // DJI mission speed cap
  EXPECT_EQ(m30.max_climb_rate_m_s, 5);         // MSDK v4 VERTICAL_CONTROL_MAX_VELOCITY
  EXPECT_EQ(m30.max_descent_rate_m_s, 4);       // MSDK v4 VERTICAL_CONTROL_MIN_VELOCITY = -4
  EXPECT_EQ(m30.min_gimbal_pitch_deg, -120);    // M30 gimbal tilt
  EXPECT_EQ(m30.dji_drone_enum, 67);            // WPML
  EXPECT_FALSE(m30.lens);
  const DroneProfile mini = *FindDroneProfile("dji-mini4pro");
  EXPECT_EQ(mini.dji_drone_enum, 68);
  EXPECT_EQ(mini.max_gimbal_pitch_deg, 60);
  ASSERT_TRUE(mini.lens);
  EXPECT_EQ(mini.lens->min_f_number, 1.7);  // fixed aperture
  EXPECT_EQ(mini.lens->max_f_number, 1.7);
}

TEST(DroneProfiles, OldNamesAreAnAliasOrRefusedWithTheNewName) {
  EXPECT_EQ(FindDroneProfile("px4_default_quad")->name, "px4-multirotor");
  EXPECT_EQ(RequireDroneProfile("px4_default_quad", "shots.json: drone").name, "px4-multirotor");
  EXPECT_FALSE(FindDroneProfile("dji_class"));
  const std::string m = testing::InputErrorMessage([] { RequireDroneProfile("dji_class", "shots.json: drone"); });
  EXPECT_NE(m.find("shots.json: drone: \"dji_class\" is no longer a profile"), std::string::npos) << m;
  EXPECT_NE(m.find("\"dji-m30\" or \"dji-mini4pro\""), std::string::npos) << m;
  EXPECT_EQ(testing::InputErrorMessage([] { RequireDroneProfile("x", "--drone"); }),
            "--drone: unknown drone profile \"x\" (known: px4-multirotor, ardupilot-copter, dji-m30, dji-mini4pro)");
}

TEST(DroneProfiles, EveryProfileIsConsistent) {
  for (const auto& name : DroneProfileNames()) {
    const DroneProfile d = *FindDroneProfile(name);
    EXPECT_EQ(d.name, name);
    EXPECT_FALSE(d.firmware.empty()) << name;
    for (const DroneProfileField& f : DroneProfileFields()) {
      if (f.check != DroneProfileField::Check::kPositive) continue;
      if (f.number) {
        EXPECT_GT(d.*f.number, 0) << name << " " << f.key;
      } else {
        EXPECT_GT(d.*f.integer, 0) << name << " " << f.key;
      }
    }
    EXPECT_LT(d.min_gimbal_pitch_deg, d.max_gimbal_pitch_deg);
    EXPECT_LT(d.min_altitude_m, d.max_altitude_m);
    EXPECT_LT(d.min_relative_altitude_m, d.max_relative_altitude_m);
  }
}

TEST(DroneProfile, JsonRoundTripThroughTheFieldTable) {
  const DroneProfile mini = *FindDroneProfile("dji-mini4pro");
  const Json j = DroneProfileToJson(mini);
  DroneProfile back;
  ApplyDroneProfileJson(JsonField(j, "plan.json", "drone"), &back);
  EXPECT_EQ(DroneProfileToJson(back), j);
  EXPECT_EQ(back.name, "dji-mini4pro");
}

TEST(DroneProfile, OverridesAreCheckedAndUnknownKeysRefused) {
  DroneProfile d = DefaultDroneProfile();
  auto apply = [&](const char* text) {
    ApplyDroneProfileJson(JsonField(Json::parse(text), "shots.json", "drone"), &d);
  };
  apply(R"({"max_horizontal_speed_m_s": 20, "max_mission_items": 100})");
  EXPECT_EQ(d.max_horizontal_speed_m_s, 20);
  EXPECT_EQ(d.max_mission_items, 100);
  EXPECT_EQ(testing::InputErrorMessage([&] { apply(R"({"max_speed": 3})"); }),
            "shots.json: drone.max_speed: unknown key in a drone profile (docs/drones.md lists the fields)");
  EXPECT_EQ(testing::InputErrorMessage([&] { apply(R"({"max_climb_rate_m_s": -1})"); }),
            "shots.json: drone.max_climb_rate_m_s: must be > 0");
  EXPECT_EQ(testing::InputErrorMessage([&] { apply(R"({"max_altitude_m": 0.5})"); }),
            "shots.json: drone.max_altitude_m: must be > min_altitude_m");
}

}  // namespace
}  // namespace cinepath
