// The drone's angles where it flies: heading from true north and gimbal pitch and roll from the local
// horizontal at the camera's own position, not at the scene's origin.
//
// The scene frame (local ENU, core/geodesy.h) is a plane tangent to the ellipsoid at the origin: its
// north and its up are the origin's. At a point d metres away, true north there is turned from the
// frame's north by the meridian convergence, about (d_east / (N cos lat)) · sin lat radians, and the
// vertical is tilted by about d / R. Both are tiny near the origin at mid latitudes (1e-3 deg at 100 m
// at 47 deg), but a compass and a gimbal's level are the local ones: 1.5 km off the origin at 89.95 deg
// the convergence is 1.3 deg, and a 1,200 mm lens sees 1.7 deg across. So every angle a plan writes
// and a mission flies (plan.json's drone_heading_deg, gimbal_pitch_deg, gimbal_roll_deg) is measured
// in the local level frame at its sample (east, north, up of the ellipsoid there), and angles a shot
// list gives at a known position are read the same way. Orientations (world_from_camera) stay in the
// scene frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>

#include "core/geodesy.h"
#include "core/rotation.h"
#include "core/trajectory.h"

namespace cinepath {

// GimbalFromWorldFromCamera against true north and the local vertical at `position_enu_m` (`frame`
// null: against the scene frame's axes, as a plan without an origin). `drone_heading_deg`: the nose's
// true heading when it is not on the camera (NaN: it is).
GimbalAngles LocalGimbalAngles(const EnuFrame* frame, const Eigen::Vector3d& position_enu_m,
                               const Eigen::Quaterniond& world_from_camera,
                               double drone_heading_deg = std::numeric_limits<double>::quiet_NaN());

// The inverse: world_from_camera (scene frame) of a camera at `position_enu_m` whose angles are taken
// against true north and the local vertical there.
Eigen::Quaterniond LocalWorldFromCamera(const EnuFrame* frame, const Eigen::Vector3d& position_enu_m,
                                        const GimbalAngles& angles);

// LookAt (core/rotation.h) levelled where the camera is: the horizon of the local vertical at
// `position_enu_m`, `fallback_heading_deg` a true heading there.
Eigen::Quaterniond LocalLookAt(const EnuFrame* frame, const Eigen::Vector3d& position_enu_m,
                               const Eigen::Vector3d& forward_enu, double fallback_heading_deg = 0.0);

// Sets the sample's drone_heading_deg and gimbal angles from its world_from_camera at its position and,
// with a frame, its geodetic position (from the same step).
void SetLocalAngles(const EnuFrame* frame, TrajectorySample& sample,
                    double drone_heading_deg = std::numeric_limits<double>::quiet_NaN());

}  // namespace cinepath
