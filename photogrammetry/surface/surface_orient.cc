#include "photogrammetry/surface/surface_orient.h"

#include <algorithm>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "photogrammetry/mesh/union_find.h"
#include "photogrammetry/surface/cgal_point_search_internal.h"

namespace cinepath::photogrammetry {
namespace {

// The mean unit direction from each point to the cameras that saw it; zero without observers.
std::vector<Eigen::Vector3d> DirectionsToObservers(const PointCloud& cloud) {
  std::vector<Eigen::Vector3d> toward(cloud.size(), Eigen::Vector3d::Zero());
  for (size_t i = 0; i < cloud.size() && i < cloud.observers.size(); ++i) {
    for (uint32_t c : cloud.observers[i]) {
      if (c >= cloud.camera_centers_m.size()) continue;
      const Eigen::Vector3d d = cloud.camera_centers_m[c] - cloud.positions_m[i];
      const double norm = d.norm();
      if (norm > 0 && std::isfinite(norm)) toward[i] += d / norm;
    }
  }
  return toward;
}

// Component of each face: the smallest vertex index of its piece (deterministic).
std::vector<uint32_t> FaceComponents(const TriangleMesh& mesh) {
  UnionFind pieces(mesh.num_vertices());
  for (const auto& f : mesh.faces) {
    pieces.Unite(f[0], f[1]);
    pieces.Unite(f[0], f[2]);
  }
  std::vector<uint32_t> component(mesh.num_faces());
  for (size_t k = 0; k < mesh.num_faces(); ++k) component[k] = pieces.Find(mesh.faces[k][0]);
  return component;
}

}  // namespace

Json OrientReport::ToJson() const {
  Json j = Json::object();
  j["components"] = components;
  j["components_flipped"] = components_flipped;
  j["faces_flipped"] = faces_flipped;
  j["faces_without_observers"] = faces_without_observers;
  return j;
}

OrientReport OrientTowardCameras(TriangleMesh* mesh, const PointCloud& cloud) {
  OrientReport report;
  const std::vector<uint32_t> component = FaceComponents(*mesh);
  std::vector<uint32_t> roots = component;
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  report.components = static_cast<int64_t>(roots.size());
  if (cloud.observers.empty() || cloud.camera_centers_m.empty() || cloud.size() == 0) {
    report.faces_without_observers = static_cast<int64_t>(mesh->num_faces());
    return report;
  }
  const std::vector<Eigen::Vector3d> toward = DirectionsToObservers(cloud);
  const internal::PointSearch search(cloud.positions_m);
  if (search.size() == 0) {  // no finite point to ask
    report.faces_without_observers = static_cast<int64_t>(mesh->num_faces());
    return report;
  }
  // Votes in face order, one sum per piece: the same sums whatever the threads.
  std::vector<double> vote(roots.size(), 0.0);
  for (size_t k = 0; k < mesh->num_faces(); ++k) {
    const auto& f = mesh->faces[k];
    const Eigen::Vector3d& a = mesh->vertices_m[f[0]];
    const Eigen::Vector3d area_normal = 0.5 * (mesh->vertices_m[f[1]] - a).cross(mesh->vertices_m[f[2]] - a);
    const Eigen::Vector3d centroid = (a + mesh->vertices_m[f[1]] + mesh->vertices_m[f[2]]) / 3.0;
    const uint32_t nearest = search.Nearest(centroid, 1).front().second;
    const double norm = toward[nearest].norm();
    if (!(norm > 0)) {
      ++report.faces_without_observers;
      continue;
    }
    const size_t piece = std::lower_bound(roots.begin(), roots.end(), component[k]) - roots.begin();
    vote[piece] += area_normal.dot(toward[nearest] / norm);
  }
  std::vector<bool> flip(roots.size());
  for (size_t p = 0; p < roots.size(); ++p) {
    flip[p] = vote[p] < 0;
    report.components_flipped += flip[p] ? 1 : 0;
  }
  for (size_t k = 0; k < mesh->num_faces(); ++k) {
    const size_t piece = std::lower_bound(roots.begin(), roots.end(), component[k]) - roots.begin();
    if (!flip[piece]) continue;
    std::swap(mesh->faces[k][1], mesh->faces[k][2]);
    ++report.faces_flipped;
  }
  return report;
}

}  // namespace cinepath::photogrammetry
