// The team checks of a plan for several drones (core/team_plan.h), on the shared clock:
//
// - separation: every pair of drones at least min_separation_m apart (the larger of the two profiles'),
//   centre to centre, at every sample;
// - in_shot: no drone's body (a sphere of its profile's body_radius_m) inside another drone's frame while
//   that camera is live in the edit, or at any time without an edit. A body counts when its projected
//   disc overlaps the image and is at least kInShotMinDiameterPx across (a smaller speck is not seen).
//   The scene's mesh does not hide a drone (a drone behind a building is still reported).
//
// A flight that ends before another holds its last position (hovering). Broken samples merge into time
// ranges, as the feasibility report does.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/team_plan.h"

namespace cinepath {

inline constexpr double kInShotMinDiameterPx = 1.0;

// The least separation any pair must keep: the largest min_separation_m of the flights' profiles.
double TeamMinSeparationM(const TeamPlan& plan);

// A drone's body seen by a camera: the diameter (px) of its projected disc, or 0 when it is behind the
// camera or its disc misses the image. Pinhole with the camera's sensor fit (core/optics.h).
double ProjectedBodyDiameterPx(const CameraSpec& camera, const Eigen::Vector3d& camera_position_enu_m,
                               const Eigen::Quaterniond& world_from_camera, double focal_length_mm,
                               const Eigen::Vector3d& body_position_enu_m, double body_radius_m);

// Recomputes plan.team.conflicts (separation, then in_shot; pairs in flight order) and min_separation_m.
// Leaves focus_matches alone.
void CheckTeam(TeamPlan& plan);

}  // namespace cinepath
