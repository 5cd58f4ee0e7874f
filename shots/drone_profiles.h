// Drone limit profiles shipped with cinepath (shots.json "drone": "<name>" or {"profile": ..., overrides}).
//
//   px4_default_quad  PX4 multicopter defaults (../shared/specs/optics.md, "Planning priors"):
//                     12 m/s horizontal (MPC_XY_VEL_MAX), climb 3 m/s, descent 1.5 m/s, acceleration
//                     5 m/s^2 (the maximum; 3 is the default), jerk 4 m/s^3, yaw rate 45 deg/s.
//   dji_class         DJI mission limits (../shared/specs/missions.md): speed <= 15 m/s, gimbal pitch
//                     -90..0 deg, altitude up to 500 m above take-off (MSDK v4 waypoint range).
// Figures the specs do not give are assumptions, marked "assumed" in docs/plan.md: gimbal pitch
// range -90..+30 and 90 deg/s pitch rate (PX4 gimbals), altitude band 1..120 m for PX4 (the open-
// category ceiling, not a PX4 parameter), the DJI climb/descent/acceleration/jerk/yaw-rate figures,
// and the 2 m keep-out (CineMPC's prior) for both.
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
