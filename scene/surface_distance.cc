#include "scene/surface_distance.h"

#include <list>
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
  scene::Tree tree;
};

SurfaceDistance::SurfaceDistance(const SceneMesh& mesh) : num_faces_(mesh.num_faces()) {
  if (mesh.faces.empty()) return;
  centre_enu_m_ = mesh.Bounds().center();
  tree_ = std::make_unique<Tree>();
  tree_->triangles.reserve(mesh.faces.size());
  const auto point = [&](uint32_t v) {
    const Eigen::Vector3d p = mesh.positions_enu_m[v] - centre_enu_m_;
    return Point(p.x(), p.y(), p.z());
  };
  for (const auto& f : mesh.faces) tree_->triangles.emplace_back(point(f[0]), point(f[1]), point(f[2]));
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
  out.behind = (point_enu_m - out.position_enu_m).dot(out.normal_enu) < 0;
  return out;
}

}  // namespace cinepath::scene
