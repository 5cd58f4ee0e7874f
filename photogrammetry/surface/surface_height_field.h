// 2.5D height-field surface for nadir drone captures, as OpenDroneMap does: a 2D Delaunay
// triangulation (CGAL) of the points' (e, n) with u lifted. Before meshing, height spikes (a point
// far above or below its Delaunay neighbours) are dropped; after meshing, triangles with an edge much
// longer than the typical spacing (the convex-hull slivers and gaps far from any input point) are
// trimmed.
#pragma once

#include <cstdint>

#include "core/json.h"
#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct HeightFieldOptions {
  // Grid thinning: when the cloud has more points than this, one point per (e, n) cell (the median
  // height) is kept, the cell sized so about max_points remain. 0 = never thin.
  int64_t max_points = 2000000;
  // Spike test: a point is a spike when |u − median u of its Delaunay neighbours| exceeds
  // max(spike_min_m, spike_factor × the median of that deviation over all points).
  double spike_factor = 8.0;
  double spike_min_m = 1.0;
  // A triangle is trimmed when its longest horizontal edge exceeds max_edge_factor × the
  // max_edge_percentile-th percentile of all edge lengths (COLMAP's delaunay_mesher trims the same
  // way). A percentile rather than the median keeps sparse areas of an unevenly dense cloud.
  double max_edge_factor = 4.0;
  double max_edge_percentile = 95.0;
};

struct HeightFieldReport {
  int64_t points_in = 0, points_thinned = 0, duplicate_xy_points = 0, spikes_removed = 0;
  int64_t triangles = 0, long_edge_triangles_trimmed = 0, faces_out = 0;
  double median_edge_m = 0, percentile_edge_m = 0, max_edge_m = 0;
  Json ToJson() const;
};

// Faces are counter-clockwise seen from above (normals up); colours come from the points.
// Throws InputError with fewer than 3 finite points or when all are collinear in (e, n).
TriangleMesh HeightFieldSurface(const PointCloud& cloud, const HeightFieldOptions& options, HeightFieldReport* report);

}  // namespace cinepath::photogrammetry
