// Scenes and plans the optimizer tests share: boxes (walls, pillars, buildings, a ground slab), a ground
// quad with one or both windings, and a plan from a shot list given as JSON text.
#pragma once

#include <string>

#include "core/json.h"
#include "core/trajectory.h"
#include "scene/scene_mesh.h"
#include "shots/planner.h"
#include "shots/shot_list.h"

namespace cinepath::optimizer::test_scenes {

inline Trajectory PlanFromShots(const std::string& shots_json) {
  return shots::PlanShots(shots::ParseShotList(Json::parse(shots_json), "test_shots.json"));
}

// An axis-aligned box as 12 triangles (outward faces).
inline void AddBox(scene::SceneMesh* mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const uint32_t b = mesh->positions_enu_m.size();
  for (int i = 0; i < 8; ++i) {
    mesh->positions_enu_m.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  }
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh->faces.push_back({b + q[0], b + q[1], b + q[2]});
    mesh->faces.push_back({b + q[0], b + q[2], b + q[3]});
  }
}

// A square ground of side 2 half_m at height 0 about the origin, its front up; with `both_windings` every
// triangle is there twice, once each way round (double-sided geometry), the flipped one first.
inline void AddGroundQuad(scene::SceneMesh* mesh, double half_m, bool both_windings) {
  const uint32_t b = mesh->positions_enu_m.size();
  mesh->positions_enu_m.insert(
      mesh->positions_enu_m.end(),
      {{-half_m, -half_m, 0}, {half_m, -half_m, 0}, {half_m, half_m, 0}, {-half_m, half_m, 0}});
  for (const auto& f : {std::array<uint32_t, 3>{0, 1, 2}, std::array<uint32_t, 3>{0, 2, 3}}) {
    if (both_windings) mesh->faces.push_back({b + f[0], b + f[2], b + f[1]});
    mesh->faces.push_back({b + f[0], b + f[1], b + f[2]});
  }
}

}  // namespace cinepath::optimizer::test_scenes
