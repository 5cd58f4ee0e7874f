#include "core/drone_profiles.h"

#include "core/error.h"

namespace cinepath {
namespace {

// Sources (docs/drones.md repeats them in one table):
//  [PX4]   PX4 parameter reference, https://docs.px4.io/main/en/advanced_config/parameter_reference.html:
//          MPC_XY_VEL_MAX 12 m/s, MPC_Z_VEL_MAX_UP 3 m/s, MPC_Z_VEL_MAX_DN 1.5 m/s, MPC_ACC_HOR_MAX 5 m/s^2,
//          MPC_JERK_AUTO 4 m/s^3, MPC_YAWRAUTO_MAX 45 deg/s; NUM_MISSIONS_SUPPORTED 2000 on NuttX boards.
//  [AP]    ArduCopter AC_WPNav defaults (libraries/AC_WPNav/AC_WPNav.cpp, .h): WPNAV_SPEED 10 m/s,
//          WPNAV_SPEED_UP 2.5 m/s, WPNAV_SPEED_DN 1.5 m/s, WPNAV_ACCEL 2.5 m/s^2, WPNAV_JERK 1 m/s^3;
//          ATC_SLEW_YAW 6000 cdeg/s = 60 deg/s (AC_AttitudeControl); ~724 mission items on STM32 boards
//          with 15-byte records in a 16 KiB storage area (AP_Mission).
//  [EU]    Commission Implementing Regulation (EU) 2019/947, Art. 4(1)(d): the open category stays within
//          120 m of the surface (https://eur-lex.europa.eu/legal-content/EN/TXT/HTML/?uri=CELEX:32019R0947).
//  [MSDK]  DJI Mobile SDK v4: virtual-stick limits VERTICAL_CONTROL_MAX_VELOCITY 5 m/s,
//          VERTICAL_CONTROL_MIN_VELOCITY -4 m/s, yaw angular velocity 100 deg/s; DJIGimbalSpeedRotation
//          angleVelocity [0, 120] deg/s; mission speed <= 15 m/s, altitude -200..500 m relative.
//  [WPML]  DJI WPML (Cloud API) droneEnumValue 67 = M30, 68 = Mini 4 Pro; payloadEnumValue 52 = M30
//          camera; waypoint speed [1, 15] m/s.
//  [M30]   DJI Matrice 30 specifications, https://enterprise.dji.com/matrice-30/specs: gimbal tilt -120..+45
//          deg (not checked against an aircraft).
//  [MINI4] DJI Mini 4 Pro specifications, https://www.dji.com/mini-4-pro/specs: gimbal tilt -90..+60 deg,
//          lens 24 mm equivalent (6.7 mm on its 1/1.3-inch sensor), f/1.7, focus 1 m to infinity.
//  [CMPC]  CineMPC (Pueyo et al. 2022) keep-out of 2 m around the subject.
// Figures no source gives are marked "assumed" here and in docs/drones.md.
DroneProfile Px4Multirotor() {
  return {
      .name = "px4-multirotor",
      .firmware = "px4",
      .max_horizontal_speed_m_s = 12,     // [PX4] MPC_XY_VEL_MAX
      .max_climb_rate_m_s = 3,            // [PX4] MPC_Z_VEL_MAX_UP
      .max_descent_rate_m_s = 1.5,        // [PX4] MPC_Z_VEL_MAX_DN
      .max_acceleration_m_s2 = 5,         // [PX4] MPC_ACC_HOR_MAX
      .max_jerk_m_s3 = 4,                 // [PX4] MPC_JERK_AUTO
      .max_yaw_rate_deg_s = 45,           // [PX4] MPC_YAWRAUTO_MAX
      .min_gimbal_pitch_deg = -90,        // assumed (the gimbal's range, not a PX4 parameter)
      .max_gimbal_pitch_deg = 30,         // assumed
      .max_gimbal_pitch_rate_deg_s = 90,  // assumed
      .min_altitude_m = 1,                // assumed ground clearance
      .max_altitude_m = 120,              // [EU]
      .min_subject_distance_m = 2,        // [CMPC]
      .min_terrain_clearance_m = 3,       // assumed
      .min_relative_altitude_m = -200,    // assumed (as MSDK v4)
      .max_relative_altitude_m = 500,     // assumed (as MSDK v4)
      .max_mission_items = 2000,          // [PX4] NUM_MISSIONS_SUPPORTED
      .body_radius_m = 0.4,               // assumed: a 500 mm-wheelbase quad with 10-inch propellers
      .min_separation_m = 5,              // assumed
      .lens = std::nullopt,
  };
}

DroneProfile ArdupilotCopter() {
  return {
      .name = "ardupilot-copter",
      .firmware = "ardupilot",
      .max_horizontal_speed_m_s = 10,     // [AP] WPNAV_SPEED (settable up to 20 m/s: override it)
      .max_climb_rate_m_s = 2.5,          // [AP] WPNAV_SPEED_UP
      .max_descent_rate_m_s = 1.5,        // [AP] WPNAV_SPEED_DN
      .max_acceleration_m_s2 = 2.5,       // [AP] WPNAV_ACCEL
      .max_jerk_m_s3 = 1,                 // [AP] WPNAV_JERK
      .max_yaw_rate_deg_s = 60,           // [AP] ATC_SLEW_YAW
      .min_gimbal_pitch_deg = -90,        // assumed
      .max_gimbal_pitch_deg = 30,         // assumed
      .max_gimbal_pitch_rate_deg_s = 90,  // assumed
      .min_altitude_m = 1,                // assumed
      .max_altitude_m = 120,              // [EU]
      .min_subject_distance_m = 2,        // [CMPC]
      .min_terrain_clearance_m = 3,       // assumed
      .min_relative_altitude_m = -200,    // assumed
      .max_relative_altitude_m = 500,     // assumed
      .max_mission_items = 724,           // [AP]
      .body_radius_m = 0.4,               // assumed, as px4-multirotor
      .min_separation_m = 5,              // assumed
      .lens = std::nullopt,
  };
}

DroneProfile DjiM30() {
  return {
      .name = "dji-m30",
      .firmware = "dji",
      .max_horizontal_speed_m_s = 15,      // [WPML] [MSDK] mission speed
      .max_climb_rate_m_s = 5,             // [MSDK]
      .max_descent_rate_m_s = 4,           // [MSDK]
      .max_acceleration_m_s2 = 5,          // assumed
      .max_jerk_m_s3 = 6,                  // assumed
      .max_yaw_rate_deg_s = 100,           // [MSDK]
      .min_gimbal_pitch_deg = -120,        // [M30]
      .max_gimbal_pitch_deg = 45,          // [M30]
      .max_gimbal_pitch_rate_deg_s = 120,  // [MSDK]
      .min_altitude_m = 1,                 // assumed
      .max_altitude_m = 120,               // [EU]
      .min_subject_distance_m = 2,         // [CMPC]
      .min_terrain_clearance_m = 3,        // assumed
      .min_relative_altitude_m = -200,     // [MSDK]
      .max_relative_altitude_m = 1500,     // assumed (WPML has no lower cap than the aircraft's ceiling)
      .max_mission_items = 65535,          // [WPML] waypoint count
      .dji_drone_enum = 67,                // [WPML]
      .dji_drone_sub_enum = 0,
      .dji_payload_enum = 52,  // [WPML]
      .body_radius_m = 0.55,   // [M30] 668 mm diagonal wheelbase, half of it plus a propeller's radius
      .min_separation_m = 5,   // assumed
      .lens = std::nullopt,
  };
}

DroneProfile DjiMini4Pro() {
  return {
      .name = "dji-mini4pro",
      .firmware = "dji",
      .max_horizontal_speed_m_s = 15,      // [WPML] [MSDK] mission speed
      .max_climb_rate_m_s = 5,             // [MSDK]
      .max_descent_rate_m_s = 4,           // [MSDK]
      .max_acceleration_m_s2 = 5,          // assumed
      .max_jerk_m_s3 = 6,                  // assumed
      .max_yaw_rate_deg_s = 100,           // [MSDK]
      .min_gimbal_pitch_deg = -90,         // [MINI4]
      .max_gimbal_pitch_deg = 60,          // [MINI4]
      .max_gimbal_pitch_rate_deg_s = 120,  // [MSDK]
      .min_altitude_m = 1,                 // assumed
      .max_altitude_m = 120,               // [EU]
      .min_subject_distance_m = 2,         // [CMPC]
      .min_terrain_clearance_m = 3,        // assumed
      .min_relative_altitude_m = -200,     // [MSDK]
      .max_relative_altitude_m = 500,      // [MSDK]
      .max_mission_items = 65535,          // [WPML]
      .dji_drone_enum = 68,                // [WPML]
      .dji_drone_sub_enum = 0,
      .dji_payload_enum = 0,
      .body_radius_m = 0.24,                         // [MINI4] 298 x 373 mm unfolded with propellers: half its diagonal
      .min_separation_m = 5,                         // assumed
      .lens = FixedLens{.min_focal_length_mm = 6.7,  // [MINI4] 24 mm equivalent
                        .max_focal_length_mm = 6.7,
                        .min_f_number = 1.7,  // [MINI4] fixed aperture
                        .max_f_number = 1.7,
                        .min_focus_distance_m = 1.0},  // [MINI4]
  };
}

std::vector<DroneProfile> MakeProfiles() { return {Px4Multirotor(), ArdupilotCopter(), DjiM30(), DjiMini4Pro()}; }

struct OldName {
  const char* old_name;
  const char* new_name;  // nullptr: refused
  const char* note;
};
constexpr OldName kOldNames[] = {
    {"px4_default_quad", "px4-multirotor", ""},
    {"dji_class", nullptr,
     "\"dji_class\" is no longer a profile (its limits were the MSDK v4 waypoint ranges, not one aircraft's): "
     "use \"dji-m30\" or \"dji-mini4pro\" (docs/drones.md)"},
};

}  // namespace

const std::vector<DroneProfile>& DroneProfiles() {
  static const std::vector<DroneProfile> profiles = MakeProfiles();
  return profiles;
}

std::vector<std::string> DroneProfileNames() {
  std::vector<std::string> names;
  for (const auto& p : DroneProfiles()) names.push_back(p.name);
  return names;
}

const DroneProfile& DefaultDroneProfile() { return DroneProfiles().front(); }

std::optional<DroneProfile> FindDroneProfile(std::string_view name) {
  for (const OldName& o : kOldNames) {
    if (name == o.old_name && o.new_name) name = o.new_name;
  }
  for (const auto& p : DroneProfiles()) {
    if (p.name == name) return p;
  }
  return std::nullopt;
}

DroneProfile RequireDroneProfile(std::string_view name, const std::string& where) {
  if (auto p = FindDroneProfile(name)) return *p;
  for (const OldName& o : kOldNames) {
    if (name == o.old_name) throw InputError(Located(where, o.note));
  }
  std::string known;
  for (const auto& n : DroneProfileNames()) known += (known.empty() ? "" : ", ") + n;
  throw InputError(Located(where, "unknown drone profile \"" + std::string(name) + "\" (known: " + known + ")"));
}

}  // namespace cinepath
