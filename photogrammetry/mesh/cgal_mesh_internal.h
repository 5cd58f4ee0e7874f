// INTERNAL to the CGAL translation units of cinepath_photogrammetry (mesh_clean.cc,
// mesh_distance.cc, mesh_decimate_cgal.cc, surface_*.cc). Never include it from a public header:
// CGAL headers cost ~10 s of compile time each (docs/dependencies.md).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry::internal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;

inline std::vector<Point3> PointsOf(const TriangleMesh& mesh) {
  std::vector<Point3> points;
  points.reserve(mesh.num_vertices());
  for (const auto& v : mesh.vertices_m) points.emplace_back(v.x(), v.y(), v.z());
  return points;
}

inline std::vector<std::array<uint32_t, 3>> FacesWithDistinctCorners(const TriangleMesh& mesh) {
  std::vector<std::array<uint32_t, 3>> faces;
  faces.reserve(mesh.num_faces());
  for (const auto& f : mesh.faces) {
    if (f[0] != f[1] && f[1] != f[2] && f[0] != f[2]) faces.push_back(f);
  }
  return faces;
}

// True when the triangle soup is a consistently oriented 2-manifold (with or without border):
// no triangle repeats a point, no directed edge occurs twice (so an edge has at most two faces, of
// opposite orientation), and the faces around every point form a single fan. The same condition as
// CGAL's is_polygon_soup_a_polygon_mesh for triangles, with sorted arrays instead of std::set:
// ~10× faster on million-face meshes (it dominated CleanMesh's time).
inline bool IsOrientedManifoldTriangleSoup(const std::vector<std::array<std::size_t, 3>>& faces,
                                           std::size_t num_points) {
  std::vector<uint64_t> directed;
  directed.reserve(3 * faces.size());
  for (const auto& f : faces) {
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) return false;
    for (int k = 0; k < 3; ++k) {
      if (f[k] >= num_points) return false;
      directed.push_back((static_cast<uint64_t>(f[k]) << 32) | static_cast<uint64_t>(f[(k + 1) % 3]));
    }
  }
  std::sort(directed.begin(), directed.end());
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end()) return false;
  // Faces around each point (CSR), then walk each point's link: every face (v, x, y) contributes
  // the link edge x → y; with unique directed edges the link is a union of paths and cycles, and
  // the point is manifold when it is one of them.
  std::vector<uint32_t> start(num_points + 1, 0);
  for (const auto& f : faces) {
    for (int k = 0; k < 3; ++k) ++start[f[k] + 1];
  }
  for (std::size_t i = 0; i < num_points; ++i) start[i + 1] += start[i];
  std::vector<std::pair<uint32_t, uint32_t>> link(start.back());
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& f : faces) {
      for (int k = 0; k < 3; ++k) {
        link[fill[f[k]]++] = {static_cast<uint32_t>(f[(k + 1) % 3]), static_cast<uint32_t>(f[(k + 2) % 3])};
      }
    }
  }
  for (std::size_t v = 0; v < num_points; ++v) {
    auto* begin = link.data() + start[v];
    auto* end = link.data() + start[v + 1];
    const std::size_t n = static_cast<std::size_t>(end - begin);
    if (n <= 1) continue;
    std::sort(begin, end);  // by link source x: each x has at most one outgoing link edge
    auto next = [&](uint32_t x) -> const std::pair<uint32_t, uint32_t>* {
      auto it = std::lower_bound(begin, end, std::make_pair(x, uint32_t{0}));
      return it != end && it->first == x ? it : nullptr;
    };
    // Start at a path's first link vertex (a source that is nobody's target), else anywhere.
    std::vector<uint32_t> targets;
    targets.reserve(n);
    for (auto* e = begin; e != end; ++e) targets.push_back(e->second);
    std::sort(targets.begin(), targets.end());
    uint32_t first = begin->first;
    for (auto* e = begin; e != end; ++e) {
      if (!std::binary_search(targets.begin(), targets.end(), e->first)) {
        first = e->first;
        break;
      }
    }
    std::size_t walked = 0;
    uint32_t x = first;
    for (const std::pair<uint32_t, uint32_t>* e = next(x); e != nullptr && walked <= n; e = next(x)) {
      ++walked;
      x = e->second;
      if (x == first) break;
    }
    if (walked != n) return false;
  }
  return true;
}

// Surface_mesh → TriangleMesh (vertex order = Surface_mesh iteration order, garbage skipped).
inline TriangleMesh TriangleMeshOf(const SurfaceMesh& sm) {
  TriangleMesh out;
  std::vector<uint32_t> index(sm.number_of_vertices() + sm.number_of_removed_vertices(), 0);
  out.vertices_m.reserve(sm.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    index[v.idx()] = static_cast<uint32_t>(out.vertices_m.size());
    const Point3& p = sm.point(v);
    out.vertices_m.emplace_back(p.x(), p.y(), p.z());
  }
  out.faces.reserve(sm.number_of_faces());
  for (SurfaceMesh::Face_index f : sm.faces()) {
    std::array<uint32_t, 3> tri{};
    int k = 0;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k < 3) tri[k] = index[v.idx()];
      ++k;
    }
    if (k == 3) out.faces.push_back(tri);
  }
  return out;
}

}  // namespace cinepath::photogrammetry::internal
