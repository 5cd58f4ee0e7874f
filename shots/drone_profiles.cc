#include "shots/drone_profiles.h"

namespace cinepath {

DroneLimits Px4DefaultQuadLimits() {
  DroneLimits d;
  d.name = "px4_default_quad";
  d.max_horizontal_speed_m_s = 12;
  d.max_climb_rate_m_s = 3;
  d.max_descent_rate_m_s = 1.5;
  d.max_acceleration_m_s2 = 5;
  d.max_jerk_m_s3 = 4;
  d.max_yaw_rate_deg_s = 45;
  d.min_gimbal_pitch_deg = -90;
  d.max_gimbal_pitch_deg = 30;        // assumed
  d.max_gimbal_pitch_rate_deg_s = 90; // assumed
  d.min_altitude_m = 1;               // assumed ground clearance
  d.max_altitude_m = 120;             // assumed: open-category ceiling
  d.min_subject_distance_m = 2;       // CineMPC keep-out
  return d;
}

DroneLimits DjiClassLimits() {
  DroneLimits d;
  d.name = "dji_class";
  d.max_horizontal_speed_m_s = 15;    // DJI missions: speed <= 15 m/s
  d.max_climb_rate_m_s = 5;           // assumed
  d.max_descent_rate_m_s = 4;         // assumed
  d.max_acceleration_m_s2 = 5;        // assumed (PX4 maximum)
  d.max_jerk_m_s3 = 6;                // assumed
  d.max_yaw_rate_deg_s = 90;          // assumed
  d.min_gimbal_pitch_deg = -90;       // DJI gimbal pitch -90..0
  d.max_gimbal_pitch_deg = 0;
  d.max_gimbal_pitch_rate_deg_s = 90; // assumed
  d.min_altitude_m = 1;               // assumed ground clearance
  d.max_altitude_m = 500;             // MSDK v4 waypoint altitude <= 500 m above take-off
  d.min_subject_distance_m = 2;
  return d;
}

std::optional<DroneLimits> FindDroneProfile(std::string_view name) {
  if (name == "px4_default_quad") return Px4DefaultQuadLimits();
  if (name == "dji_class") return DjiClassLimits();
  return std::nullopt;
}

std::vector<std::string_view> DroneProfileNames() { return {"px4_default_quad", "dji_class"}; }

}  // namespace cinepath
