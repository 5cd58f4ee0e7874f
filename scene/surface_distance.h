// Distance from a point to the scene's surface: what `optimize` keeps the drone away from (clearance)
// and asks of the ground around a flight. A CGAL AABB tree over the triangles, built once; queries
// return the closest surface point, so a cost can take the gradient (p - q) / |p - q| exactly.
//
// Build it over the corridor a flight can reach, not the whole scene: CropToBox (scene/scene_mesh.h)
// first. Positions are re-centred about the box centre before they go into the tree (doubles either
// way; re-centring keeps the tree's arithmetic at metres, not kilometres). Queries are const,
// thread-safe and deterministic (a query gives the same point on every run).
#pragma once

#include <memory>
#include <optional>

#include <Eigen/Core>

#include "scene/scene_mesh.h"

namespace cinepath::scene {

struct SurfacePoint {
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  double distance_m = 0;
  Eigen::Vector3d normal_enu = Eigen::Vector3d::UnitZ();  // unit normal of the closest face (counter-clockwise front)
  // The query point lies behind the closest face ((p - q) . n < 0): inside a closed, outward-facing solid,
  // or under terrain. A distance cost then pushes towards q, not away from it. Never for a face the mesh
  // also holds with the other winding (double-sided geometry): such a sheet has no inside, and its
  // normal is given on the point's side.
  bool behind = false;
};

class SurfaceDistance {
 public:
  // An empty mesh is allowed: every query then returns nullopt.
  explicit SurfaceDistance(const SceneMesh& mesh);
  ~SurfaceDistance();
  SurfaceDistance(const SurfaceDistance&) = delete;
  SurfaceDistance& operator=(const SurfaceDistance&) = delete;

  // The closest point of the surface to `point_enu_m`; nullopt for an empty mesh.
  std::optional<SurfacePoint> Closest(const Eigen::Vector3d& point_enu_m) const;
  size_t num_faces() const { return num_faces_; }

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
  Eigen::Vector3d centre_enu_m_ = Eigen::Vector3d::Zero();
  size_t num_faces_ = 0;
};

}  // namespace cinepath::scene
