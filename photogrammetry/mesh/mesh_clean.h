// Mesh cleaning for photogrammetry surfaces with CGAL
// Polygon_mesh_processing: invalid and degenerate faces, duplicate vertices and faces, non-manifold
// vertices and edges, small connected components / floating blobs, holes up to a size (never the
// outer boundary of an open terrain mesh), isolated vertices. Every count goes into CleanReport.
//
// Speed: duplicates are found with hash tables, and the soup's topology (oriented
// 2-manifold or not, components, border cycles) is read from a per-point corner table. When the
// soup is an oriented 2-manifold — the common case, once bowtie points are split — no Surface_mesh of the whole mesh is
// built: small components are dropped from the soup and CGAL fills each hole on a local Surface_mesh made of the faces
// around it. Other soups go through CGAL's soup orientation and Surface_mesh repairs. Parallel loops run over fixed
// chunks: the result is the same at any thread count.
#pragma once

#include <cstdint>

#include "core/json.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct MeshCleanOptions {
  // A connected component is dropped when it has fewer faces than
  // max(min_component_faces, min_component_fraction × faces of the largest component).
  int64_t min_component_faces = 50;
  double min_component_fraction = 0.01;
  // A boundary cycle is filled when it has at most max_hole_edges edges and a perimeter of at most
  // max_hole_perimeter_m; the longest boundary of each component is its outer border and is never
  // filled. 0 disables hole filling.
  int64_t max_hole_edges = 200;
  double max_hole_perimeter_m = 50.0;
  // Faces whose area is below this (m²) count as degenerate. Exact zero-area faces always do.
  double min_face_area_m2 = 1e-12;
};

struct MeshCleanReport {
  int64_t vertices_in = 0, faces_in = 0;
  int64_t invalid_faces_removed = 0;        // index out of range, repeated corner, non-finite vertex
  int64_t degenerate_faces_removed = 0;     // zero (or tiny) area
  int64_t duplicate_vertices_merged = 0;    // exactly equal positions
  int64_t duplicate_faces_removed = 0;      // same three vertices, either orientation
  int64_t non_manifold_vertices_split = 0;  // points duplicated to make the surface a 2-manifold
  int64_t faces_reoriented = 0;
  int64_t small_components_removed = 0;
  int64_t faces_in_small_components = 0;
  int64_t components_kept = 0;
  int64_t borders_stitched = 0;  // halfedge pairs zipped back after removing sheets
  int64_t holes_filled = 0;
  int64_t hole_faces_added = 0;
  int64_t holes_left_open = 0;  // boundaries too large to be holes (incl. outer borders)
  int64_t isolated_vertices_removed = 0;
  int64_t vertices_out = 0, faces_out = 0;
  // Which repair path ran: the oriented-manifold soup fast path (after splitting bowties, if any)
  // or CGAL's soup orientation and Surface_mesh repairs.
  bool general_path = false;
  Json ToJson() const;
};

// Returns a manifold, consistently oriented mesh. Colours follow their vertices; vertices added
// by hole filling get the mean colour of the hole's border.
TriangleMesh CleanMesh(const TriangleMesh& mesh, const MeshCleanOptions& options, MeshCleanReport* report);

}  // namespace cinepath::photogrammetry
