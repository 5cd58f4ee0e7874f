// Trimming a reconstructed surface to the support of its data, and flattening spikes.
//
// Poisson closes every surface and a Delaunay height field spans the convex hull, so both invent
// surface where no point was measured: a skirt past every open border, and border triangles stretched
// between stray points. This step removes what the points do not support and flattens what stands out
// of the local surface, and reports every count with the criterion that caused it.
//
// Local spacing: at each data point, the mean distance to its `spacing_neighbours` nearest points
// (a k-NN spacing: about 1.1 × the grid pitch of a regular grid for k = 6), then the median of that over
// its 16 nearest points (so a clump of near-duplicates or a lone stray point does not set the scale),
// and at least min_spacing_m (the surface's own resolution: a Poisson mesh's facets are about the
// mesher's radius, its vertices that far from the points). Every criterion below is a multiple of the
// local spacing of the data point nearest to where it is measured, so a sparse area is judged against
// its own density.
//
// 1. Far from the data: a face whose centroid or a corner is farther from the nearest data point than
//    far_factor × that point's spacing is removed, wherever it is.
// 2. Border peeling: repeatedly, a face with an edge on the border is removed when its centroid or a
//    corner is farther than border_factor × spacing from the data, or when its longest edge exceeds
//    border_edge_factor × spacing (the largest spacing at its corners; a border triangle stretched
//    between scattered points). Interior faces are left alone: a gap in the middle of the data is
//    bridged, as the height field does.
//    2b. Ears and strays: a face whose longest edge exceeds ear_edge_factor × spacing is removed when
//    two or more of its edges are on the border (an ear: it hangs from the surface by one edge or
//    none), or when one of its corners is a stray, a border vertex with one or two faces, both that
//    stretched (a lone point the surface reached out to). Up to max_ear_passes passes, so the cut
//    reaches a few triangles in and never peels ring after ring: the part of step 2 that stays safe on
//    a sparse cloud's clumpy border, where peeling eats into the data.
//    2c. Border fit: a border vertex short of the data (points lie past it, within border_extend_factor ×
//    spacing, on a plane around it) is moved out to the farthest of those points: onto that point, less
//    its offset along the border, so at the point's own height and never past the points (Poisson rounds
//    a sheet over at a free edge, and the roll is cut away); a border vertex past the data (farther
//    from its nearest data point than border_pull_factor × that point's spacing) is moved straight toward
//    the point until it is that far. Both use the points' own k-NN spacing (not floored by min_spacing_m),
//    and a move that would turn a face around it by more than 60° is halved (up to three times) or else
//    not made. Faces are removed a whole face at a time, so a Poisson border, whose facets are ~1.5 point
//    spacings, otherwise ends up to a facet out past the points (and curls off their plane there), or
//    more than a spacing short of a free edge.
// 3. Spikes: a vertex whose distance to the least-squares plane of its one-ring neighbours exceeds
//    max(spike_min_m, spike_factor × the mean length of its edges) is moved onto that plane (smoothed,
//    not cut); up to spike_passes passes. The report keeps the largest such height found.
// 4. Onto the points: a vertex with data points under it (its nearest point within settle_factor × that
//    point's own spacing) goes along the normal of the plane of the points within that radius (8 at
//    least) onto it, when they lie on one (RMS under a third of a spacing: not at a crease). Where the
//    points are thin (an orbit's outer ring) Poisson's smooth implicit surface bows away from them between
//    the points by metres; the points themselves are within centimetres. A move that would turn a face by
//    more than 60° is halved or not made, as in 2c. Where fewer than 8 points lie within the radius (a
//    thin outer ring, the spacing capped), the 8 nearest within twice the radius. With settle_creases
//    (the Poisson path) the points are first fitted robustly (surface_crease.h): where two surfaces meet
//    (a cliff's foot or top edge, a wall on the ground) and the points lie on two planes within a third
//    of a spacing (85 % of them, the planes at 25° or more), the vertex goes to the nearest point of the
//    two half-planes; where one plane carries 75 % of them and the rest are too few for a second, onto
//    that plane; a move longer than the radius is not made. Poisson rounds such an edge over a metre or
//    more, and a least-squares plane through both surfaces' points can pass the RMS test tilted.
#pragma once

#include <cstdint>

#include "core/json.h"
#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct SurfaceTrimOptions {
  int spacing_neighbours = 6;
  double min_spacing_m = 0;
  double far_factor = 3.0;            // 0 = skip step 1
  double border_factor = 1.0;         // 0 = skip the distance test of step 2
  double border_edge_factor = 4.0;    // 0 = skip the edge test of step 2
  int max_border_passes = 1000;       // a bound on the peeling (each pass removes one ring of faces)
  double ear_edge_factor = 4.0;       // 0 = skip step 2b
  int max_ear_passes = 3;             // a bound on step 2b (each pass cuts what is an ear or stray then)
  double border_pull_factor = 0.5;    // 0 = skip step 2c
  double border_extend_factor = 3.0;  // 0 = step 2c only pulls (never moves a vertex out to the data)
  double spike_factor = 1.0;          // 0 = skip step 3
  double spike_min_m = 0.25;
  int spike_passes = 3;
  double settle_factor = 0;     // 0 = skip step 4 (the Poisson path of surface_pipeline.cc sets it)
  bool settle_creases = false;  // step 4 also onto two planes where the points hold an edge (Poisson path)
  // Every local spacing at most this × the points' median spacing (0 = no cap; the Poisson path sets it):
  // in a thin outer ring the points are metres apart, and 3 such spacings kept faces 60 m from any point.
  double max_spacing_ratio = 0;
};

struct SurfaceTrimReport {
  int64_t faces_in = 0, faces_out = 0;
  int64_t faces_far_from_data = 0;       // step 1
  int64_t border_faces_unsupported = 0;  // step 2, distance test
  int64_t border_faces_stretched = 0;    // step 2, edge test
  int64_t border_passes = 0;
  int64_t border_ears_cut = 0;  // step 2b
  int64_t ear_passes = 0;
  int64_t border_vertices_pulled = 0;        // step 2c
  int64_t border_pulls_refused = 0;          // step 2c: moves taken back (a face would turn)
  int64_t border_moves_shortened = 0;        // step 2c: moves kept at 1/2, 1/4 or 1/8 (a face would turn)
  double max_border_pull_m = 0;              // the longest move
  int64_t border_vertices_extended = 0;      // step 2c: moved out to the data's border
  double max_border_extension_m = 0;         // the longest such move
  int64_t spike_vertices_flattened = 0;      // step 3 (a vertex flattened in two passes counts twice)
  double max_spike_height_m = 0;             // largest distance to the ring plane among flattened vertices
  int64_t settle_vertices_moved = 0;         // step 4
  int64_t settle_moves_refused = 0;          // step 4: moves taken back (a face would turn)
  int64_t settle_crease_vertices_moved = 0;  // step 4: of the moved, those onto two planes (a crease)
  double max_settle_move_m = 0;              // the longest such move
  int64_t spacings_capped = 0;               // points whose spacing max_spacing_ratio capped
  double median_spacing_m = 0;               // median local spacing over the data points
  double median_point_spacing_m = 0;         // the same, not floored by min_spacing_m (the points' own)
  SurfaceTrimOptions options;                // the criteria, as run
  Json ToJson() const;
};

// `points` are the data the surface was built from (ENU metres). Vertices no face uses any more are
// dropped; colours follow their vertices. Deterministic at any thread count.
TriangleMesh TrimSurfaceToData(const TriangleMesh& mesh, const PointCloud& points, const SurfaceTrimOptions& options,
                               SurfaceTrimReport* report);

}  // namespace cinepath::photogrammetry
