#include "photogrammetry/mesh_clean.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>
#include <vector>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/boost/graph/iterator.h>

#include "core/error.h"
#include "photogrammetry/cgal_mesh_internal.h"

namespace cinepath::photogrammetry {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using internal::Point3;
using internal::SurfaceMesh;
using Color = std::array<uint8_t, 3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using FaceIndex = SurfaceMesh::Face_index;
using HalfedgeIndex = SurfaceMesh::Halfedge_index;

struct UnionFind {
  std::vector<uint32_t> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t Find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void Unite(uint32_t a, uint32_t b) {
    a = Find(a);
    b = Find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

bool SameCyclicOrder(const std::array<size_t, 3>& polygon, const std::array<uint32_t, 3>& face,
                     const std::vector<size_t>& original_of_point) {
  for (int shift = 0; shift < 3; ++shift) {
    bool same = true;
    for (int k = 0; k < 3 && same; ++k) {
      same = original_of_point[polygon[k]] == face[(k + shift) % 3];
    }
    if (same) return true;
  }
  return false;
}

}  // namespace

Json MeshCleanReport::ToJson() const {
  Json j;
  j["vertices_in"] = vertices_in;
  j["faces_in"] = faces_in;
  j["invalid_faces_removed"] = invalid_faces_removed;
  j["degenerate_faces_removed"] = degenerate_faces_removed;
  j["duplicate_vertices_merged"] = duplicate_vertices_merged;
  j["duplicate_faces_removed"] = duplicate_faces_removed;
  j["non_manifold_vertices_split"] = non_manifold_vertices_split;
  j["faces_reoriented"] = faces_reoriented;
  j["small_components_removed"] = small_components_removed;
  j["faces_in_small_components"] = faces_in_small_components;
  j["components_kept"] = components_kept;
  j["borders_stitched"] = borders_stitched;
  j["holes_filled"] = holes_filled;
  j["hole_faces_added"] = hole_faces_added;
  j["holes_left_open"] = holes_left_open;
  j["isolated_vertices_removed"] = isolated_vertices_removed;
  j["vertices_out"] = vertices_out;
  j["faces_out"] = faces_out;
  return j;
}

TriangleMesh CleanMesh(const TriangleMesh& mesh, const MeshCleanOptions& options,
                       MeshCleanReport* report_out) {
  MeshCleanReport report;
  report.vertices_in = static_cast<int64_t>(mesh.num_vertices());
  report.faces_in = static_cast<int64_t>(mesh.num_faces());
  const size_t n = mesh.num_vertices();
  const bool colored = mesh.has_colors() && mesh.colors_rgb.size() == n;

  // 1. Merge vertices with exactly equal positions (the lowest index represents the group).
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  auto key = [&](uint32_t i) {
    const auto& v = mesh.vertices_m[i];
    return std::make_tuple(v.x(), v.y(), v.z(), i);
  };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
  std::vector<uint32_t> representative(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = order[k];
    if (k > 0 && mesh.vertices_m[order[k - 1]] == mesh.vertices_m[i]) {
      representative[i] = representative[order[k - 1]];
      ++report.duplicate_vertices_merged;
    } else {
      representative[i] = i;
    }
  }

  // 2. Invalid, degenerate and duplicate faces.
  std::vector<std::array<uint32_t, 3>> faces;
  faces.reserve(mesh.num_faces());
  std::vector<std::array<uint32_t, 3>> seen_keys;
  seen_keys.reserve(mesh.num_faces());
  for (const auto& f : mesh.faces) {
    bool valid = true;
    for (uint32_t i : f) valid = valid && i < n && mesh.vertices_m[i].allFinite();
    if (!valid || f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
      ++report.invalid_faces_removed;
      continue;
    }
    const std::array<uint32_t, 3> r{representative[f[0]], representative[f[1]],
                                    representative[f[2]]};
    const Eigen::Vector3d& a = mesh.vertices_m[r[0]];
    const Eigen::Vector3d& b = mesh.vertices_m[r[1]];
    const Eigen::Vector3d& c = mesh.vertices_m[r[2]];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2] || area < options.min_face_area_m2 ||
        CGAL::collinear(Point3(a.x(), a.y(), a.z()), Point3(b.x(), b.y(), b.z()),
                        Point3(c.x(), c.y(), c.z()))) {
      ++report.degenerate_faces_removed;
      continue;
    }
    faces.push_back(r);
  }
  {
    std::vector<uint32_t> face_order(faces.size());
    std::iota(face_order.begin(), face_order.end(), 0u);
    std::vector<std::array<uint32_t, 3>> sorted_keys(faces.size());
    for (size_t i = 0; i < faces.size(); ++i) {
      sorted_keys[i] = faces[i];
      std::sort(sorted_keys[i].begin(), sorted_keys[i].end());
    }
    std::stable_sort(face_order.begin(), face_order.end(),
                     [&](uint32_t a, uint32_t b) { return sorted_keys[a] < sorted_keys[b]; });
    std::vector<char> keep(faces.size(), 1);
    for (size_t k = 1; k < face_order.size(); ++k) {
      if (sorted_keys[face_order[k]] == sorted_keys[face_order[k - 1]]) {
        keep[face_order[k]] = 0;
        ++report.duplicate_faces_removed;
      }
    }
    std::vector<std::array<uint32_t, 3>> unique_faces;
    unique_faces.reserve(faces.size());
    for (size_t i = 0; i < faces.size(); ++i) {
      if (keep[i]) unique_faces.push_back(faces[i]);
    }
    faces.swap(unique_faces);
  }

  // 3. Compact: vertices no face uses are isolated (merged duplicates are counted above).
  std::vector<int64_t> compact(n, -1);
  std::vector<size_t> original_of_point;
  std::vector<Point3> points;
  for (const auto& f : faces) {
    for (uint32_t i : f) {
      if (compact[i] < 0) compact[i] = 0;
    }
  }
  for (size_t i = 0; i < n; ++i) {
    if (compact[i] == 0) {
      compact[i] = static_cast<int64_t>(points.size());
      original_of_point.push_back(i);
      const auto& v = mesh.vertices_m[i];
      points.emplace_back(v.x(), v.y(), v.z());
    } else if (representative[i] == i) {
      ++report.isolated_vertices_removed;
    }
  }
  if (faces.empty()) {
    if (report_out) *report_out = report;
    return TriangleMesh{};
  }
  // Fixed-size polygons: no allocation per face (millions of faces).
  std::vector<std::array<size_t, 3>> polygons(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    polygons[i] = {static_cast<size_t>(compact[faces[i][0]]),
                   static_cast<size_t>(compact[faces[i][1]]),
                   static_cast<size_t>(compact[faces[i][2]])};
  }

  // 4. Non-manifold edges and vertices: orient the soup; CGAL duplicates the points where the
  //    surface is not a 2-manifold. Then keep each component in the orientation most of its input
  //    faces had (orienting may flip a whole component).
  if (!internal::IsOrientedManifoldTriangleSoup(polygons, points.size())) {
    const size_t points_before = points.size();
    PMP::orient_polygon_soup(points, polygons);
    report.non_manifold_vertices_split = static_cast<int64_t>(points.size() - points_before);
    // Points added by CGAL are copies: find their originals by position.
    std::map<std::tuple<double, double, double>, size_t> original_by_position;
    for (size_t p = 0; p < points_before; ++p) {
      original_by_position.emplace(std::make_tuple(points[p].x(), points[p].y(), points[p].z()),
                                   original_of_point[p]);
    }
    for (size_t p = points_before; p < points.size(); ++p) {
      original_of_point.push_back(original_by_position.at(
          std::make_tuple(points[p].x(), points[p].y(), points[p].z())));
    }
    UnionFind components(points.size());
    for (const auto& polygon : polygons) {
      components.Unite(static_cast<uint32_t>(polygon[0]), static_cast<uint32_t>(polygon[1]));
      components.Unite(static_cast<uint32_t>(polygon[0]), static_cast<uint32_t>(polygon[2]));
    }
    std::map<uint32_t, std::pair<int64_t, int64_t>> flipped_and_total;
    std::vector<char> flipped(polygons.size());
    for (size_t i = 0; i < polygons.size(); ++i) {
      flipped[i] = !SameCyclicOrder(polygons[i], faces[i], original_of_point);
      auto& counts = flipped_and_total[components.Find(static_cast<uint32_t>(polygons[i][0]))];
      counts.first += flipped[i];
      counts.second += 1;
    }
    for (size_t i = 0; i < polygons.size(); ++i) {
      const auto& counts =
          flipped_and_total[components.Find(static_cast<uint32_t>(polygons[i][0]))];
      if (2 * counts.first > counts.second) {
        std::reverse(polygons[i].begin(), polygons[i].end());
        flipped[i] = !flipped[i];
      }
      report.faces_reoriented += flipped[i];
    }
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  auto color_map = sm.add_property_map<VertexIndex, Color>("v:color", Color{0, 0, 0}).first;
  {
    // polygon_soup_to_polygon_mesh creates the vertices in point order.
    size_t p = 0;
    for (VertexIndex v : sm.vertices()) {
      CINEPATH_CHECK(p < points.size() && sm.point(v) == points[p]);
      if (colored) color_map[v] = mesh.colors_rgb[original_of_point[p]];
      ++p;
    }
  }
  {
    std::vector<HalfedgeIndex> non_manifold;
    PMP::non_manifold_vertices(sm, std::back_inserter(non_manifold));
    if (!non_manifold.empty()) {
      report.non_manifold_vertices_split +=
          static_cast<int64_t>(PMP::duplicate_non_manifold_vertices(sm));
    }
  }

  // 5. Small components and floating blobs.
  {
    auto cc_map = sm.add_property_map<FaceIndex, std::size_t>("f:cc", 0).first;
    const std::size_t num_components = PMP::connected_components(sm, cc_map);
    std::vector<int64_t> faces_per_component(num_components, 0);
    for (FaceIndex f : sm.faces()) ++faces_per_component[cc_map[f]];
    const int64_t largest =
        *std::max_element(faces_per_component.begin(), faces_per_component.end());
    const int64_t threshold = std::max<int64_t>(
        options.min_component_faces,
        static_cast<int64_t>(std::ceil(options.min_component_fraction * largest)));
    for (int64_t count : faces_per_component) {
      if (count < threshold && count < largest) {
        ++report.small_components_removed;
        report.faces_in_small_components += count;
      } else {
        ++report.components_kept;
      }
    }
    if (report.small_components_removed > 0) {
      const int64_t keep_threshold = std::min(threshold, largest);
      PMP::keep_large_connected_components(sm, static_cast<std::size_t>(keep_threshold));
    }
    sm.remove_property_map(cc_map);
  }
  // Non-manifold edges were cut open by orienting; once the extra sheets are gone, zip the slits.
  report.borders_stitched = static_cast<int64_t>(PMP::stitch_borders(sm));

  // 6. Holes up to a size; the longest boundary of each component is its outer border.
  if (options.max_hole_edges > 0 && options.max_hole_perimeter_m > 0) {
    auto cc_map = sm.add_property_map<FaceIndex, std::size_t>("f:cc", 0).first;
    const std::size_t num_components = PMP::connected_components(sm, cc_map);
    std::vector<HalfedgeIndex> cycles;
    PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
    struct Cycle {
      HalfedgeIndex h;
      int64_t edges = 0;
      double perimeter_m = 0;
      std::size_t component = 0;
    };
    std::vector<Cycle> info;
    std::vector<double> longest(num_components, -1.0);
    for (HalfedgeIndex h : cycles) {
      Cycle c;
      c.h = h;
      for (HalfedgeIndex e : CGAL::halfedges_around_face(h, sm)) {
        ++c.edges;
        c.perimeter_m += std::sqrt(CGAL::squared_distance(sm.point(sm.source(e)),
                                                          sm.point(sm.target(e))));
      }
      c.component = cc_map[sm.face(sm.opposite(h))];
      longest[c.component] = std::max(longest[c.component], c.perimeter_m);
      info.push_back(c);
    }
    std::vector<char> outer_taken(num_components, 0);
    sm.remove_property_map(cc_map);
    for (const Cycle& c : info) {
      const bool outer = !outer_taken[c.component] && c.perimeter_m == longest[c.component];
      if (outer) outer_taken[c.component] = 1;
      if (outer || c.edges > options.max_hole_edges ||
          c.perimeter_m > options.max_hole_perimeter_m) {
        ++report.holes_left_open;
        continue;
      }
      // Border colour: the mean over the hole's vertices.
      std::array<double, 3> sum{0, 0, 0};
      for (HalfedgeIndex e : CGAL::halfedges_around_face(c.h, sm)) {
        for (int k = 0; k < 3; ++k) sum[k] += color_map[sm.target(e)][k];
      }
      std::vector<FaceIndex> new_faces;
      std::vector<VertexIndex> new_vertices;
      PMP::triangulate_and_refine_hole(sm, c.h, std::back_inserter(new_faces),
                                       std::back_inserter(new_vertices));
      if (new_faces.empty()) {
        ++report.holes_left_open;
        continue;
      }
      ++report.holes_filled;
      report.hole_faces_added += static_cast<int64_t>(new_faces.size());
      Color mean;
      for (int k = 0; k < 3; ++k) {
        mean[k] = static_cast<uint8_t>(std::lround(sum[k] / static_cast<double>(c.edges)));
      }
      for (VertexIndex v : new_vertices) color_map[v] = mean;
    }
  }

  // 7. Isolated vertices left by the steps above.
  report.isolated_vertices_removed += static_cast<int64_t>(PMP::remove_isolated_vertices(sm));
  sm.collect_garbage();

  TriangleMesh out = internal::TriangleMeshOf(sm);
  if (colored) {
    out.colors_rgb.reserve(out.vertices_m.size());
    for (VertexIndex v : sm.vertices()) out.colors_rgb.push_back(color_map[v]);
  }
  report.vertices_out = static_cast<int64_t>(out.num_vertices());
  report.faces_out = static_cast<int64_t>(out.num_faces());
  if (report_out) *report_out = report;
  return out;
}

}  // namespace cinepath::photogrammetry
