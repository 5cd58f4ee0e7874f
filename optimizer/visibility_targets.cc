#include "optimizer/visibility_targets.h"

#include <cmath>
#include <vector>

namespace cinepath::optimizer {

bool LineOfSightBlocked(const scene::RayCaster& caster, const Eigen::Vector3d& camera_enu_m,
                        const Eigen::Vector3d& aim_enu_m) {
  const Eigen::Vector3d d = aim_enu_m - camera_enu_m;
  const double length = d.norm();
  if (length < 0.4) return false;
  return caster.Occluded(camera_enu_m, d / length, 0.05, length - 0.3);
}

std::optional<Eigen::Vector3d> NearestClearViewpoint(const scene::RayCaster& caster,
                                                     const scene::SurfaceDistance* surface,
                                                     const Eigen::Vector3d& camera_enu_m,
                                                     const Eigen::Vector3d& aim_enu_m, double max_radius_m,
                                                     double clearance_margin_m, double overshoot_m) {
  // Directions: up, then 8 compass directions (from "away from the subject", clockwise) at 60, 30, 0 deg.
  Eigen::Vector3d away = camera_enu_m - aim_enu_m;
  away.z() = 0;
  const double away_heading = away.norm() > 1e-9 ? std::atan2(away.x(), away.y()) : 0.0;
  std::vector<Eigen::Vector3d> directions = {Eigen::Vector3d::UnitZ()};
  for (double elevation_deg : {60.0, 30.0, 0.0}) {
    const double el = elevation_deg * M_PI / 180.0;
    for (int i = 0; i < 8; ++i) {
      const double heading = away_heading + i * M_PI / 4.0;
      directions.emplace_back(std::cos(el) * std::sin(heading), std::cos(el) * std::cos(heading), std::sin(el));
    }
  }
  // A viewpoint that sees the aim point, is reached without passing through the mesh, and keeps the margin.
  const auto usable = [&](const Eigen::Vector3d& u, double radius) {
    const Eigen::Vector3d candidate = camera_enu_m + radius * u;
    if (LineOfSightBlocked(caster, candidate, aim_enu_m)) return false;
    if (caster.Occluded(camera_enu_m, u, 0.0, radius)) return false;
    if (surface) {
      const auto closest = surface->Closest(candidate);
      if (closest && (closest->behind || closest->distance_m < clearance_margin_m)) return false;
    }
    return true;
  };
  for (double radius = 0.5; radius <= max_radius_m + 1e-9; radius += 0.5) {
    for (const Eigen::Vector3d& u : directions) {
      if (!usable(u, radius)) continue;
      const double further = std::min(radius + overshoot_m, max_radius_m);
      return camera_enu_m + (further > radius && usable(u, further) ? further : radius) * u;
    }
  }
  return std::nullopt;
}

}  // namespace cinepath::optimizer
