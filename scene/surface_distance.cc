#include "scene/surface_distance.h"

#include <algorithm>
#include <array>
#include <list>
#include <unordered_map>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

namespace cinepath::scene {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;
using Traits = CGAL::AABB_traits<Kernel, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;
}  // namespace

struct SurfaceDistance::Tree {
  std::vector<Triangle> triangles;
  std::vector<bool> two_sided;  // per triangle: the mesh also has it with the other winding
  scene::Tree tree;
};

namespace {
// A face's corners in a canonical order (the smallest first, keeping the winding), and the same for the
// other winding: a triangle and its twin give the same key the other way round.
using FaceKey = std::array<std::array<double, 3>, 3>;
FaceKey KeyOf(std::array<std::array<double, 3>, 3> c) {
  const int first = static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin());
  return {c[first], c[(first + 1) % 3], c[(first + 2) % 3]};
}
struct FaceKeyHash {
  size_t operator()(const FaceKey& key) const {
    size_t h = 0;
    for (const auto& corner : key) {
      for (double x : corner) h = h * 1000003u ^ std::hash<double>()(x);
    }
    return h;
  }
};
}  // namespace

SurfaceDistance::SurfaceDistance(const SceneMesh& mesh) : num_faces_(mesh.num_faces()) {
  if (mesh.faces.empty()) return;
  centre_enu_m_ = mesh.Bounds().center();
  tree_ = std::make_unique<Tree>();
  tree_->triangles.reserve(mesh.faces.size());
  tree_->two_sided.reserve(mesh.faces.size());
  const auto point = [&](uint32_t v) {
    const Eigen::Vector3d p = mesh.positions_enu_m[v] - centre_enu_m_;
    return Point(p.x(), p.y(), p.z());
  };
  // A face present with both windings (double-sided geometry) is a sheet with no inside: it is kept once,
  // marked two-sided, so that the closest face of a point over it is one face, never its flipped twin.
  std::unordered_map<FaceKey, size_t, FaceKeyHash> kept;  // winding-keeping key -> triangle index
  for (const auto& f : mesh.faces) {
    std::array<std::array<double, 3>, 3> c;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d& p = mesh.positions_enu_m[f[i]];
      c[i] = {p.x(), p.y(), p.z()};
    }
    const auto twin = kept.find(KeyOf({c[0], c[2], c[1]}));
    if (twin != kept.end()) {
      tree_->two_sided[twin->second] = true;
      continue;
    }
    kept.emplace(KeyOf(c), tree_->triangles.size());
    tree_->triangles.emplace_back(point(f[0]), point(f[1]), point(f[2]));
    tree_->two_sided.push_back(false);
  }
  tree_->tree.insert(tree_->triangles.begin(), tree_->triangles.end());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;

std::optional<SurfacePoint> SurfaceDistance::Closest(const Eigen::Vector3d& point_enu_m) const {
  if (!tree_) return std::nullopt;
  const Eigen::Vector3d local = point_enu_m - centre_enu_m_;
  const auto hit = tree_->tree.closest_point_and_primitive(Point(local.x(), local.y(), local.z()));
  const Point& q = hit.first;
  const Triangle& t = *hit.second;
  SurfacePoint out;
  out.position_enu_m = Eigen::Vector3d(q.x(), q.y(), q.z()) + centre_enu_m_;
  out.distance_m = (out.position_enu_m - point_enu_m).norm();
  const auto n = CGAL::cross_product(t.vertex(1) - t.vertex(0), t.vertex(2) - t.vertex(0));
  const Eigen::Vector3d normal(n.x(), n.y(), n.z());
  if (normal.norm() > 0) out.normal_enu = normal.normalized();
  const size_t index = static_cast<size_t>(hit.second - tree_->triangles.begin());
  if (tree_->two_sided[index]) {
    // A sheet: its front is the side the point is on.
    if ((point_enu_m - out.position_enu_m).dot(out.normal_enu) < 0) out.normal_enu = -out.normal_enu;
    return out;
  }
  out.behind = (point_enu_m - out.position_enu_m).dot(out.normal_enu) < 0;
  return out;
}

}  // namespace cinepath::scene
