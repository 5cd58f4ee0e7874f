// CGAL Surface_mesh_simplification (Garland–Heckbert plane / probabilistic plane policies), kept in
// its own translation unit: internal::DecimateCgal in mesh_decimate.h.
//
// GCC 12 warns that the Garland–Heckbert policies' per-vertex 4 × 4 quadric (a CGAL dynamic property
// of Eigen matrices) "may be used uninitialized" where CGAL copies it; the policy's initialize() puts a
// zero matrix at every vertex before any is read, so it is a false positive inside CGAL's headers,
// silenced for this file alone.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <algorithm>
#include <vector>

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Constrained_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_probabilistic_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include "core/error.h"
#include "photogrammetry/mesh/cgal_mesh_internal.h"
#include "photogrammetry/mesh/mesh_decimate.h"

namespace cinepath::photogrammetry::internal {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
namespace SMS = CGAL::Surface_mesh_simplification;
using EdgeIndex = SurfaceMesh::Edge_index;
using VertexIndex = SurfaceMesh::Vertex_index;

template <typename Policies>
void Collapse(SurfaceMesh& sm, int64_t target_faces) {
  // Border edges are constrained: the outer border of a terrain tile stays where it is.
  auto constrained = sm.add_property_map<EdgeIndex, bool>("e:constrained", false).first;
  for (EdgeIndex e : sm.edges()) constrained[e] = sm.is_border(e);
  Policies policies(sm);
  using Placement = SMS::Bounded_normal_change_placement<
      SMS::Constrained_placement<typename Policies::Get_placement, decltype(constrained)>>;
  const Placement placement(SMS::Constrained_placement<typename Policies::Get_placement, decltype(constrained)>(
      constrained, policies.get_placement()));
  // Count_stop_predicate counts edges: a triangle mesh has about 1.5 edges per face.
  const std::size_t target_edges = static_cast<std::size_t>(1.5 * static_cast<double>(target_faces));
  SMS::Count_stop_predicate<SurfaceMesh> stop(target_edges);
  SMS::edge_collapse(
      sm, stop,
      CGAL::parameters::get_cost(policies.get_cost()).get_placement(placement).edge_is_constrained_map(constrained));
}

}  // namespace

TriangleMesh DecimateCgal(const TriangleMesh& mesh, int64_t target_faces, bool probabilistic) {
  std::vector<Point3> points = PointsOf(mesh);
  std::vector<std::array<std::size_t, 3>> polygons;
  polygons.reserve(mesh.num_faces());
  for (const auto& f : FacesWithDistinctCorners(mesh)) polygons.push_back({f[0], f[1], f[2]});
  if (polygons.empty()) throw InputError("decimate: the mesh has no face");
  const std::size_t points_in = points.size();
  if (!internal::IsOrientedManifoldTriangleSoup(polygons, points.size())) PMP::orient_polygon_soup(points, polygons);
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  // Which input vertex each Surface_mesh vertex came from (copies made by orienting map to the
  // first vertex with the same position: only the colour needs it).
  auto original = sm.add_property_map<VertexIndex, uint32_t>("v:original", 0).first;
  {
    std::size_t p = 0;
    for (VertexIndex v : sm.vertices()) {
      original[v] = static_cast<uint32_t>(p < points_in ? p : 0);
      ++p;
    }
  }
  if (probabilistic) {
    Collapse<SMS::GarlandHeckbert_probabilistic_plane_policies<SurfaceMesh, Kernel>>(sm, target_faces);
  } else {
    Collapse<SMS::GarlandHeckbert_plane_policies<SurfaceMesh, Kernel>>(sm, target_faces);
  }
  sm.collect_garbage();
  TriangleMesh out = TriangleMeshOf(sm);
  if (mesh.has_colors()) {
    for (VertexIndex v : sm.vertices()) out.colors_rgb.push_back(mesh.colors_rgb[original[v]]);
  }
  return out;
}

}  // namespace cinepath::photogrammetry::internal
