// INTERNAL to the steps that move a surface's vertices onto its data (surface_trim.cc's border fit,
// surface_fit.cc): the least-squares plane of some points, and the guard that keeps a set of moves from
// turning faces over.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry::internal {

// The least-squares plane of `points`: centroid, unit normal, and whether the points span a plane
// (collinear points, a strip one triangle wide, define none).
struct FittedPlane {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero(), normal = Eigen::Vector3d::UnitZ();
  bool valid = false;
};

inline FittedPlane FitPlane(const std::vector<Eigen::Vector3d>& points) {
  FittedPlane plane;
  if (points.size() < 3) return plane;
  for (const auto& p : points) plane.centroid += p;
  plane.centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - plane.centroid) * (p - plane.centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  plane.normal = solver.eigenvectors().col(0);
  plane.valid = solver.eigenvalues()(1) > 1e-6 * std::max(solver.eigenvalues()(2), 1e-30);
  return plane;
}

// Vertex i moves to target[i] where moved[i] != 0, all together. A move that would turn a face around it
// by more than 60 degrees (or flatten it) is halved, up to three times, and then not made (moved[i] = 0);
// the check is repeated until no face turns (each round only shortens moves or takes them back).
// halvings[i]: how many times vertex i's move was halved. Returns how many moves were taken back.
inline int64_t KeepFacesFromTurning(const TriangleMesh& mesh, std::vector<Eigen::Vector3d>& target,
                                    std::vector<char>& moved, std::vector<int>& halvings) {
  constexpr int kMaxHalvings = 3;
  const size_t n = mesh.num_vertices();
  halvings.assign(n, 0);
  int64_t refused = 0;
  auto normal = [](const std::array<uint32_t, 3>& t, const std::vector<Eigen::Vector3d>& at) {
    return Eigen::Vector3d((at[t[1]] - at[t[0]]).cross(at[t[2]] - at[t[0]]));
  };
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<Eigen::Vector3d> trial = mesh.vertices_m;
    for (size_t i = 0; i < n; ++i) {
      if (moved[i]) trial[i] = target[i];
    }
    std::vector<char> undo(n, 0);
    for (const auto& t : mesh.faces) {
      if (!moved[t[0]] && !moved[t[1]] && !moved[t[2]]) continue;
      const Eigen::Vector3d before = normal(t, mesh.vertices_m), after = normal(t, trial);
      if (after.norm() > 1e-3 * before.norm() && after.dot(before) >= 0.5 * after.norm() * before.norm()) continue;
      for (uint32_t c : t) undo[c] = moved[c] != 0;
    }
    for (size_t i = 0; i < n; ++i) {
      if (!undo[i]) continue;
      changed = true;
      if (++halvings[i] <= kMaxHalvings) {  // try half the move
        target[i] = 0.5 * (target[i] + mesh.vertices_m[i]);
        continue;
      }
      moved[i] = 0;
      ++refused;
    }
  }
  return refused;
}

}  // namespace cinepath::photogrammetry::internal
