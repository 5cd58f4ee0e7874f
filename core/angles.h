// Angle units and normalization — the one place angles are wrapped.
//
// Conventions used across cinepath:
//   * Inside the libraries angles are radians; files and people see degrees (`yaw_deg`).
//   * ENU heading ("yaw_enu"): counter-clockwise from east (+x), as atan2(north, east).
//   * Compass heading ("heading_deg"): clockwise from true north, [0, 360), as drones and maps use.
//     heading = 90° − yaw_enu (in degrees), normalized.
#pragma once

#include <cmath>
#include <numbers>

namespace cinepath {

constexpr double kPi = std::numbers::pi;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr double kRadPerDeg = std::numbers::pi / 180.0;

constexpr double RadFromDeg(double deg) { return deg * kRadPerDeg; }
constexpr double DegFromRad(double rad) { return rad * kDegPerRad; }

// Reduces to [-180, 180] (exact: std::remainder). +180 stays +180, -180 becomes -180 per remainder's
// ties-to-even rule; callers who need a half-open range use NormalizeDeg180Open.
inline double NormalizeDeg180(double deg) {
  const double r = std::remainder(deg, 360.0);
  return r == 0.0 ? 0.0 : r;  // no -0
}
// Reduces to (-180, 180].
inline double NormalizeDeg180Open(double deg) {
  const double r = NormalizeDeg180(deg);
  return r == -180.0 ? 180.0 : r;
}
// Reduces to [0, 360).
inline double NormalizeDeg360(double deg) {
  double r = std::fmod(deg, 360.0);
  if (r < 0) r += 360.0;
  if (r >= 360.0) r -= 360.0;  // fmod(-tiny) + 360 can round to 360
  return r == 0.0 ? 0.0 : r;
}
// Radian versions: (-pi, pi] and [0, 2 pi).
inline double NormalizeRadPi(double rad) {
  double r = std::remainder(rad, 2.0 * kPi);
  if (r <= -kPi) r += 2.0 * kPi;
  return r == 0.0 ? 0.0 : r;
}
// Shortest signed difference b − a in degrees, in (-180, 180].
inline double AngleDiffDeg(double a_deg, double b_deg) { return NormalizeDeg180Open(b_deg - a_deg); }

// Compass heading (clockwise from north, [0,360)) from an ENU yaw (counter-clockwise from east, rad).
inline double HeadingDegFromEnuYaw(double yaw_enu_rad) { return NormalizeDeg360(90.0 - DegFromRad(yaw_enu_rad)); }
// ENU yaw (rad, (-pi, pi]) from a compass heading in degrees.
inline double EnuYawFromHeadingDeg(double heading_deg) { return NormalizeRadPi(RadFromDeg(90.0 - heading_deg)); }

}  // namespace cinepath
