#include "photogrammetry/mesh/mesh_remesh.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include "core/error.h"
#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/cgal_mesh_internal.h"
#include "photogrammetry/mesh/mesh_colors.h"

namespace cinepath::photogrammetry {

namespace PMP = CGAL::Polygon_mesh_processing;
using internal::SurfaceMesh;

void RemeshOptions::Check() const {
  if (!(target_edge_m > 0 && std::isfinite(target_edge_m))) {
    throw InputError("remesh_edge_m: must be a finite number > 0");
  }
  if (iterations < 1) throw InputError("remesh: iterations must be >= 1");
}

Json RemeshReport::ToJson() const {
  Json j;
  j["faces_in"] = faces_in;
  j["faces_out"] = faces_out;
  j["vertices_out"] = vertices_out;
  j["iterations"] = iterations;
  j["edge_min_m"] = RoundToDecimals(edge_min_m, 4);
  j["edge_mean_m"] = RoundToDecimals(edge_mean_m, 4);
  j["edge_max_m"] = RoundToDecimals(edge_max_m, 4);
  j["edges_in_band_fraction"] = RoundToDecimals(edges_in_band_fraction, 4);
  return j;
}

TriangleMesh RemeshIsotropic(const TriangleMesh& mesh, const RemeshOptions& options, RemeshReport* report_out) {
  options.Check();
  std::vector<internal::Point3> points = internal::PointsOf(mesh);
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(mesh.num_faces());
  for (const auto& f : internal::FacesWithDistinctCorners(mesh)) {
    if (f[0] >= points.size() || f[1] >= points.size() || f[2] >= points.size()) continue;
    polygons.push_back({f[0], f[1], f[2]});
  }
  if (polygons.empty()) throw InputError("remesh: the mesh has no face");
  if (!internal::IsOrientedManifoldTriangleSoup(polygons, points.size())) {
    PMP::orient_polygon_soup(points, polygons);
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  RemeshReport report;
  report.faces_in = static_cast<int64_t>(sm.number_of_faces());
  report.iterations = options.iterations;
  // The border stays put: its edges are split to the target length, then protected (neither
  // split nor collapsed; their vertices do not move), so a terrain tile keeps its outline.
  auto constrained = sm.add_property_map<SurfaceMesh::Edge_index, bool>("e:constrained", false).first;
  std::vector<SurfaceMesh::Edge_index> border;
  for (auto e : sm.edges()) {
    if (sm.is_border(e)) {
      constrained[e] = true;
      border.push_back(e);
    }
  }
  PMP::split_long_edges(border, options.target_edge_m, sm, CGAL::parameters::edge_is_constrained_map(constrained));
  // Sequential: CGAL's remeshing has no parallel mode, and its result depends only on the input.
  PMP::isotropic_remeshing(faces(sm), options.target_edge_m, sm,
                           CGAL::parameters::number_of_iterations(static_cast<unsigned int>(options.iterations))
                               .edge_is_constrained_map(constrained)
                               .protect_constraints(true));
  sm.collect_garbage();
  TriangleMesh out = internal::TriangleMeshOf(sm);

  // Edge-length statistics (each undirected edge once).
  const double lo = 0.8 * options.target_edge_m, hi = 4.0 / 3.0 * options.target_edge_m;
  int64_t edges = 0, in_band = 0;
  double sum = 0;
  report.edge_min_m = INFINITY;
  for (auto e : sm.edges()) {
    const double length =
        std::sqrt(CGAL::squared_distance(sm.point(sm.source(sm.halfedge(e))), sm.point(sm.target(sm.halfedge(e)))));
    ++edges;
    sum += length;
    report.edge_min_m = std::min(report.edge_min_m, length);
    report.edge_max_m = std::max(report.edge_max_m, length);
    in_band += length >= lo && length <= hi;
  }
  if (edges > 0) {
    report.edge_mean_m = sum / static_cast<double>(edges);
    report.edges_in_band_fraction = static_cast<double>(in_band) / static_cast<double>(edges);
  } else {
    report.edge_min_m = 0;
  }
  report.faces_out = static_cast<int64_t>(out.num_faces());
  report.vertices_out = static_cast<int64_t>(out.num_vertices());

  if (mesh.has_colors() && mesh.colors_rgb.size() == mesh.num_vertices() && out.num_faces() > 0) {
    PointCloud source;
    source.positions_m = mesh.vertices_m;
    source.colors_rgb = mesh.colors_rgb;
    ColorVerticesFromPoints(out, source);
  }
  if (report_out) *report_out = report;
  return out;
}

}  // namespace cinepath::photogrammetry
