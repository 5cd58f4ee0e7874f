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
  d.max_gimbal_pitch_deg = 30;         // assumed (no PX4 default: the gimbal's own range)
  d.max_gimbal_pitch_rate_deg_s = 90;  // assumed (no PX4 default)
  d.min_altitude_m = 1;                // assumed ground clearance
  // Not a PX4 parameter but the legal ceiling of the EU "open" category: Commission Implementing
  // Regulation (EU) 2019/947, Article 4(1)(d), "maintained within 120 metres from the closest point
  // of the surface of the earth" (https://eur-lex.europa.eu/legal-content/EN/TXT/HTML/?uri=CELEX:32019R0947).
  d.max_altitude_m = 120;
  d.min_subject_distance_m = 2;  // CineMPC keep-out
  return d;
}

DroneLimits DjiClassLimits() {
  DroneLimits d;
  d.name = "dji_class";
  d.max_horizontal_speed_m_s = 15;  // DJI missions: speed <= 15 m/s (missions.md 4.1/4.2)
  // DJI Mobile SDK v4 flight-controller limits for SDK-commanded flight
  // (dji.common.flightcontroller.virtualstick.Limits,
  // https://developer.dji.com/api-reference/android-api/Components/FlightController/DJIFlightController_Limits.html):
  // VERTICAL_CONTROL_MAX_VELOCITY = 5 m/s up (the constant; its description text says 4 m/s),
  // VERTICAL_CONTROL_MIN_VELOCITY = -4 m/s down.
  d.max_climb_rate_m_s = 5;
  d.max_descent_rate_m_s = 4;
  d.max_acceleration_m_s2 = 5;  // assumed (PX4 maximum)
  d.max_jerk_m_s3 = 6;          // assumed
  // DJIVirtualStickYawControlMaxAngularVelocity = 100 deg/s (MSDK v4 DJIFlightControllerDataType,
  // https://developer.dji.com/iframe/mobile-sdk-doc/android/reference/dji/common/flightcontroller/DJIFlightControllerDataType.html).
  d.max_yaw_rate_deg_s = 100;
  d.min_gimbal_pitch_deg = -90;  // DJI gimbal pitch -90..0 (MSDK v4 waypoint gimbalPitch, missions.md 4.2)
  d.max_gimbal_pitch_deg = 0;
  // DJIGimbalSpeedRotation.angleVelocity range [0, 120] deg/s (MSDK iOS,
  // https://developer.dji.com/iframe/mobile-sdk-doc/ios/Structs/DJIGimbalSpeedRotation.html).
  d.max_gimbal_pitch_rate_deg_s = 120;
  d.min_altitude_m = 1;    // assumed ground clearance
  d.max_altitude_m = 500;  // MSDK v4 waypoint altitude <= 500 m above take-off
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
