// Lines of sight from the camera to the subject's aim point, checked exactly by ray casting against the
// scene (scene/ray_caster.h), and for a blocked one the nearest viewpoint that sees the subject: the
// target the occlusion term pulls the camera towards (optimizer/cost_terms.h, ClearViewCost).
//
// The search is deterministic: radii 0.5 m, 1 m, ... up to the shot's max_deviation_m, and at each
// radius the directions straight up, then 8 compass directions at elevations of 60, 30 and 0 degrees
// (starting from the direction away from the subject); the first that sees the aim point and keeps the
// clearance margin from the mesh wins; it is then moved `overshoot_m` further along the same direction when
// that point is within the radius and clear too (a pull stops a little short of its target). Why targets and not a
// penetration integral: docs/optimize.md, "Occlusion".
#pragma once

#include <optional>

#include <Eigen/Core>

#include "scene/ray_caster.h"
#include "scene/surface_distance.h"

namespace cinepath::optimizer {

// Whether the mesh hides `aim_enu_m` from `camera_enu_m` (the last 0.3 m before the aim point and the
// first 5 cm after the camera are not tested: the subject's own ground, the camera's own point).
bool LineOfSightBlocked(const scene::RayCaster& caster, const Eigen::Vector3d& camera_enu_m,
                        const Eigen::Vector3d& aim_enu_m);

std::optional<Eigen::Vector3d> NearestClearViewpoint(const scene::RayCaster& caster,
                                                     const scene::SurfaceDistance* surface,
                                                     const Eigen::Vector3d& camera_enu_m,
                                                     const Eigen::Vector3d& aim_enu_m, double max_radius_m,
                                                     double clearance_margin_m, double overshoot_m = 0);

}  // namespace cinepath::optimizer
