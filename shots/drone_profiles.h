// Drone limit profiles shipped with cinepath (shots.json "drone": "<name>" or {"profile": ..., overrides}).
//
//   px4_default_quad  PX4 multicopter defaults (../shared/specs/optics.md, "Planning priors"):
//                     12 m/s horizontal (MPC_XY_VEL_MAX), climb 3 m/s, descent 1.5 m/s, acceleration
//                     5 m/s^2 (the maximum; 3 is the default), jerk 4 m/s^3, yaw rate 45 deg/s.
//   dji_class         DJI mission limits (../shared/specs/missions.md): speed <= 15 m/s, gimbal pitch
//                     -90..0 deg, altitude up to 500 m above take-off (MSDK v4 waypoint range);
//                     climb 5 / descent 4 m/s, yaw 100 deg/s, gimbal 120 deg/s from the DJI Mobile
//                     SDK's documented limits (sources in drone_profiles.cc).
// The PX4 120 m ceiling is the EU open-category limit (Regulation (EU) 2019/947), not a PX4 parameter.
// Figures no source gives stay assumptions, marked "// assumed" in drone_profiles.cc and listed in
// docs/export.md: PX4 gimbal pitch up to +30 deg and 90 deg/s, the 1 m ground clearance of both, the
// DJI acceleration (5 m/s^2) and jerk (6 m/s^3); the 2 m keep-out is CineMPC's prior.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "core/trajectory.h"

namespace cinepath {

DroneLimits Px4DefaultQuadLimits();
DroneLimits DjiClassLimits();
std::optional<DroneLimits> FindDroneProfile(std::string_view name);
std::vector<std::string_view> DroneProfileNames();

}  // namespace cinepath
