// Vertex colours from point colours: each vertex takes the inverse-distance weighted mean of the
// sRGB colours of its k nearest points (CGAL kd-tree). Deterministic: ties broken by point order.
#pragma once

#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

// Replaces mesh.colors_rgb. Throws InputError if the cloud has no colours or no points.
void ColorVerticesFromPoints(TriangleMesh& mesh, const PointCloud& cloud, int neighbours = 4);

}  // namespace cinepath::photogrammetry
