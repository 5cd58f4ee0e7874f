// Optional isotropic remeshing (`cinepath mesh --remesh-edge-m L`): CGAL Polygon_mesh_processing
// isotropic_remeshing (Botsch & Kobbelt's split / collapse / flip / tangential relaxation), which
// drives edge lengths into about [4/5 L, 4/3 L] with vertices projected back onto the input
// surface. The outer border stays where it is: border edges longer than L are split, then kept
// (never collapsed, their vertices never move). CGAL stays inside mesh_remesh.cc.
#pragma once

#include <cstdint>

#include "core/json.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct RemeshOptions {
  double target_edge_m = 1.0;  // > 0
  int iterations = 3;          // CGAL's default
  void Check() const;          // throws InputError naming the option
};

struct RemeshReport {
  int64_t faces_in = 0, faces_out = 0, vertices_out = 0;
  int iterations = 0;
  double edge_min_m = 0, edge_mean_m = 0, edge_max_m = 0;
  double edges_in_band_fraction = 0;  // share of edges within [4/5 L, 4/3 L]
  Json ToJson() const;
};

// Returns the remeshed mesh (manifold, oriented like the input). Colours, when the input has them,
// come from the nearest input vertices. Throws InputError when the mesh has no face.
TriangleMesh RemeshIsotropic(const TriangleMesh& mesh, const RemeshOptions& options, RemeshReport* report = nullptr);

}  // namespace cinepath::photogrammetry
