#include "photogrammetry/surface/surface_poisson.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include <CGAL/IO/facets_in_complex_2_to_triangle_mesh.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Poisson_reconstruction_function.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_complex_2_in_triangulation_3.h>
#include <CGAL/Surface_mesh_default_criteria_3.h>
#include <CGAL/compute_average_spacing.h>
#include <CGAL/exceptions.h>
#include <CGAL/jet_estimate_normals.h>
#include <CGAL/make_surface_mesh.h>
#include <CGAL/property_map.h>

#include "core/error.h"
#include "photogrammetry/surface/cgal_point_search_internal.h"
// cgal_poisson_order_internal.h first: before anything instantiates CGAL's triangulations.
#include "photogrammetry/surface/cgal_poisson_order_internal.h"

namespace cinepath::photogrammetry {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Vector = Kernel::Vector_3;
using PointWithNormal = std::pair<Point, Vector>;
using PointMap = CGAL::First_of_pair_property_map<PointWithNormal>;
using NormalMap = CGAL::Second_of_pair_property_map<PointWithNormal>;
using Mesh = CGAL::Surface_mesh<Point>;

// Vertices in lexicographic order of their coordinates, each face starting at its smallest index (its
// winding kept), faces sorted. The surface mesher walks sets ordered by cell addresses, so the same
// triangles come out in an order that depends on the allocator (another thread, another run); sorted,
// the same surface gives the same bytes.
void SortCanonically(TriangleMesh* mesh) {
  const size_t n = mesh->vertices_m.size();
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  const auto& v = mesh->vertices_m;
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return std::lexicographical_compare(v[a].data(), v[a].data() + 3, v[b].data(), v[b].data() + 3);
  });
  std::vector<uint32_t> new_index(n);
  std::vector<Eigen::Vector3d> sorted(n);
  for (uint32_t i = 0; i < n; ++i) {
    new_index[order[i]] = i;
    sorted[i] = v[order[i]];
  }
  mesh->vertices_m = std::move(sorted);
  for (auto& f : mesh->faces) {
    for (auto& i : f) i = new_index[i];
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
  }
  std::sort(mesh->faces.begin(), mesh->faces.end());
}

// The cloud's finite points, as CGAL points.
std::vector<Point> FinitePoints(const PointCloud& cloud) {
  std::vector<Point> points;
  points.reserve(cloud.size());
  for (const auto& p : cloud.positions_m) {
    if (p.allFinite()) points.emplace_back(p.x(), p.y(), p.z());
  }
  return points;
}

// The guard of MergeCoincidentPoints on the solver's input: drops every point merged into an earlier one,
// and reports how many and within what distance.
void MergeCoincident(const PoissonOptions& options, std::vector<PointWithNormal>* points, std::vector<uint32_t>* source,
                     PoissonReport* report) {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(points->size());
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  double largest_coordinate = 0;
  for (const auto& pn : *points) {
    positions.emplace_back(pn.first.x(), pn.first.y(), pn.first.z());
    lo = lo.cwiseMin(positions.back());
    hi = hi.cwiseMax(positions.back());
    largest_coordinate = std::max(largest_coordinate, positions.back().cwiseAbs().maxCoeff());
  }
  if (positions.empty()) return;
  const double tolerance_m = options.coincident_distance_ratio * std::max((hi - lo).norm(), largest_coordinate);
  report->coincident_distance_m = tolerance_m;
  const std::vector<uint32_t> into = MergeCoincidentPoints(positions, tolerance_m);
  size_t kept = 0;
  for (size_t j = 0; j < points->size(); ++j) {
    if (into[j] != j) continue;
    (*points)[kept] = (*points)[j];
    (*source)[kept] = (*source)[j];
    ++kept;
  }
  report->coincident_points_merged = static_cast<int64_t>(points->size() - kept);
  points->resize(kept);
  source->resize(kept);
}

}  // namespace

std::optional<std::string> PoissonInputProblem(const PointCloud& cloud) {
  const std::vector<Point> points = FinitePoints(cloud);
  if (points.size() < 10) return "fewer than 10 usable points (" + std::to_string(points.size()) + ")";
  // The affine dimension, one witness at a time: a second point, a third off their line, a fourth off
  // their plane.
  const Point& a = points.front();
  const auto b = std::find_if(points.begin(), points.end(), [&](const Point& p) { return p != a; });
  if (b == points.end()) return "all " + std::to_string(points.size()) + " points coincide";
  const auto c = std::find_if(points.begin(), points.end(), [&](const Point& p) { return !CGAL::collinear(a, *b, p); });
  if (c == points.end()) return "all " + std::to_string(points.size()) + " points lie on one line";
  const bool solid = std::any_of(points.begin(), points.end(),
                                 [&](const Point& p) { return CGAL::orientation(a, *b, *c, p) != CGAL::COPLANAR; });
  if (!solid) return "all " + std::to_string(points.size()) + " points lie on one plane";
  return std::nullopt;
}

std::vector<uint32_t> MergeCoincidentPoints(const std::vector<Eigen::Vector3d>& positions_m, double tolerance_m) {
  std::vector<uint32_t> into(positions_m.size());
  std::iota(into.begin(), into.end(), 0u);
  if (!(tolerance_m > 0)) return into;
  const internal::PointSearch search(positions_m);
  const double tolerance2 = tolerance_m * tolerance_m;
  for (uint32_t i = 0; i < positions_m.size(); ++i) {
    if (into[i] != i || !positions_m[i].allFinite()) continue;
    // The neighbours within the tolerance: ask for more until the farthest returned is beyond it.
    for (int k = 8;; k *= 4) {
      const auto near = search.Nearest(positions_m[i], k);
      for (const auto& [d2, j] : near) {
        if (d2 <= tolerance2 && j > i && into[j] == j) into[j] = i;
      }
      if (near.size() < static_cast<size_t>(k) || near.back().first > tolerance2) break;
    }
  }
  return into;
}

Json PoissonReport::ToJson() const {
  Json j;
  j["points"] = points;
  j["coincident_points_merged"] = coincident_points_merged;
  j["coincident_distance_m"] = coincident_distance_m;
  j["normals_estimated"] = normals_estimated;
  j["normals_flipped_toward_cameras"] = normals_flipped_toward_cameras;
  j["normals_oriented_up"] = normals_oriented_up;
  j["average_spacing_m"] = average_spacing_m;
  j["faces_reconstructed"] = faces_reconstructed;
  j["faces_trimmed"] = faces_trimmed;
  j["faces_out"] = faces_out;
  return j;
}

namespace {

// The finite points with their normals (zero where the cloud has none), and the cloud index of each.
void FinitePoints(const PointCloud& cloud, std::vector<PointWithNormal>* points, std::vector<uint32_t>* source) {
  for (uint32_t i = 0; i < cloud.size(); ++i) {
    const auto& p = cloud.positions_m[i];
    if (!p.allFinite()) continue;
    Vector n(0, 0, 0);
    if (cloud.has_normals() && cloud.normals[i].allFinite()) {
      n = Vector(cloud.normals[i].x(), cloud.normals[i].y(), cloud.normals[i].z());
    }
    points->emplace_back(Point(p.x(), p.y(), p.z()), n);
    source->push_back(i);
  }
}

// Normals: estimated by jet fitting when the cloud has none, then oriented toward the cameras that saw
// each point (mean direction to them), or up when nobody is recorded.
void OrientNormals(const PointCloud& cloud, const std::vector<uint32_t>& source, int k,
                   std::vector<PointWithNormal>* points, PoissonReport* report) {
  if (!cloud.has_normals()) {
    report->normals_estimated = true;
    CGAL::jet_estimate_normals<CGAL::Sequential_tag>(*points, k,
                                                     CGAL::parameters::point_map(PointMap()).normal_map(NormalMap()));
  }
  for (size_t j = 0; j < points->size(); ++j) {
    const uint32_t i = source[j];
    Vector toward(0, 0, 1);
    bool from_cameras = false;
    if (i < cloud.observers.size() && !cloud.observers[i].empty()) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (uint32_t c : cloud.observers[i]) {
        if (c >= cloud.camera_centers_m.size()) continue;
        const Eigen::Vector3d d = cloud.camera_centers_m[c] - cloud.positions_m[i];
        if (d.norm() > 0) sum += d.normalized();
      }
      if (sum.norm() > 0) {
        toward = Vector(sum.x(), sum.y(), sum.z());
        from_cameras = true;
      }
    }
    if ((*points)[j].second * toward < 0) {
      (*points)[j].second = -(*points)[j].second;
      ++(from_cameras ? report->normals_flipped_toward_cameras : report->normals_oriented_up);
    }
  }
}

// CGAL::poisson_surface_reconstruction_delaunay's steps, with the surface mesher on a triangulation whose
// handles compare in creation order (cgal_poisson_order_internal.h). RuntimeError when CGAL fails.
Mesh MeshImplicitSurface(const std::vector<PointWithNormal>& points, double spacing_m, const PoissonOptions& options) {
  // CGAL's surface mesher seeds its first points from CGAL::get_default_random(), a thread-local generator
  // that CGAL seeds with the wall clock (std::time) on first use: the same input gave another mesh every
  // second. Reset it to a fixed seed first, so the surface depends on the input alone.
  CGAL::get_default_random() = CGAL::Random(options.seed);
  // And CGAL walks its triangulations in creation order, not in address order (see the header).
  const internal::CreationOrderScope creation_order;
  Mesh sm;
  using Function = CGAL::Poisson_reconstruction_function<Kernel>;
  using Complex = CGAL::Surface_mesh_complex_2_in_triangulation_3<internal::PoissonMesherTriangulation>;
  try {
    Function function(points.begin(), points.end(), PointMap(), NormalMap());
    if (!function.compute_implicit_function()) throw RuntimeError("poisson: CGAL's Poisson solver failed");
    // The mesher's bounding sphere: 5 × the points' bounding sphere, about the function's inner point;
    // its bisection stops at distance_factor × spacing / 1000 (CGAL's convenience function's choice).
    const double sphere_radius_m = 5.0 * std::sqrt(function.bounding_sphere().squared_radius());
    const double bisection_error_m = options.distance_factor * spacing_m / 1000.0;
    const CGAL::Implicit_surface_3<Kernel, Function> surface(
        function, Kernel::Sphere_3(function.get_inner_point(), sphere_radius_m * sphere_radius_m),
        bisection_error_m / sphere_radius_m);
    const CGAL::Surface_mesh_default_criteria_3<internal::PoissonMesherTriangulation> criteria(
        options.angle_deg, options.radius_factor * spacing_m, options.distance_factor * spacing_m);
    internal::PoissonMesherTriangulation triangulation;
    Complex complex(triangulation);
    CGAL::make_surface_mesh(complex, surface, criteria, CGAL::Manifold_with_boundary_tag());
    if (triangulation.number_of_vertices() == 0) throw RuntimeError("poisson: CGAL's surface mesher found no surface");
    CGAL::facets_in_complex_2_to_triangle_mesh(complex, sm);
  } catch (const CGAL::Failure_exception& e) {
    std::string what = e.message();
    while (!what.empty() && std::isspace(static_cast<unsigned char>(what.back()))) what.pop_back();
    // A nearly flat cloud seen from above gives an implicit function the surface mesher cannot sample
    // (it meets the same point twice); the height field is the surface for such a scene (the pipeline
    // falls back to it, or names it).
    throw RuntimeError("poisson: CGAL's surface mesher failed (" + what + ")");
  }
  return sm;
}

// The mesher's triangles as a TriangleMesh, without those whose centroid is farther than max_distance_m
// from every input point (with trim_factor > 0).
TriangleMesh TrimmedTriangles(const Mesh& sm, const internal::PointSearch& search, double max_distance_m,
                              const PoissonOptions& options, PoissonReport* report) {
  TriangleMesh mesh;
  std::vector<int64_t> remap(sm.number_of_vertices() + sm.number_of_removed_vertices(), -1);
  for (Mesh::Face_index f : sm.faces()) {
    std::array<Mesh::Vertex_index, 3> v;
    int n = 0;
    for (Mesh::Vertex_index u : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (n < 3) v[n] = u;
      ++n;
    }
    if (n != 3) continue;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (auto u : v) centroid += Eigen::Vector3d(sm.point(u).x(), sm.point(u).y(), sm.point(u).z());
    centroid /= 3.0;
    if (options.trim_factor > 0 && std::sqrt(search.Nearest(centroid, 1).front().first) > max_distance_m) {
      ++report->faces_trimmed;
      continue;
    }
    std::array<uint32_t, 3> tri{};
    for (int c = 0; c < 3; ++c) {
      if (remap[v[c].idx()] < 0) {
        remap[v[c].idx()] = static_cast<int64_t>(mesh.vertices_m.size());
        const Point& q = sm.point(v[c]);
        mesh.vertices_m.emplace_back(q.x(), q.y(), q.z());
      }
      tri[c] = static_cast<uint32_t>(remap[v[c].idx()]);
    }
    mesh.faces.push_back(tri);
  }
  return mesh;
}

}  // namespace

TriangleMesh PoissonSurface(const PointCloud& cloud, const PoissonOptions& options, PoissonReport* report_out) {
  PoissonReport report;
  std::vector<PointWithNormal> points;
  std::vector<uint32_t> source;
  FinitePoints(cloud, &points, &source);
  if (const auto problem = PoissonInputProblem(cloud)) {
    throw InputError("poisson: " + *problem + ": CGAL's Poisson solver needs points that span a volume");
  }
  MergeCoincident(options, &points, &source, &report);
  report.points = static_cast<int64_t>(points.size());
  if (points.size() < 10) {
    throw InputError("poisson: fewer than 10 distinct points (" + std::to_string(points.size()) +
                     ") once coincident points are merged");
  }
  const int k = std::max(3, std::min<int>(options.normal_neighbours, static_cast<int>(points.size()) - 1));
  OrientNormals(cloud, source, k, &points, &report);
  report.average_spacing_m =
      CGAL::compute_average_spacing<CGAL::Sequential_tag>(points, k, CGAL::parameters::point_map(PointMap()));
  if (!(report.average_spacing_m > 0)) {
    throw InputError("poisson: the points have no spacing (all coincide)");
  }
  const Mesh sm =
      MeshImplicitSurface(points, report.average_spacing_m * std::max(options.spacing_factor, 1e-3), options);
  report.faces_reconstructed = static_cast<int64_t>(sm.number_of_faces());

  // Trim: drop triangles whose centroid is far from every input point.
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(points.size());
  for (const auto& pn : points) positions.emplace_back(pn.first.x(), pn.first.y(), pn.first.z());
  const internal::PointSearch search(positions);
  TriangleMesh mesh = TrimmedTriangles(sm, search, options.trim_factor * report.average_spacing_m, options, &report);
  SortCanonically(&mesh);
  if (cloud.has_colors() && mesh.num_vertices() > 0) {
    mesh.colors_rgb.reserve(mesh.num_vertices());
    for (const auto& v : mesh.vertices_m) {
      mesh.colors_rgb.push_back(cloud.colors_rgb[source[search.Nearest(v, 1).front().second]]);
    }
  }
  report.faces_out = static_cast<int64_t>(mesh.num_faces());
  if (report_out) *report_out = report;
  return mesh;
}

}  // namespace cinepath::photogrammetry
