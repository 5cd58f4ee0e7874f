// Distances between meshes: CGAL's approximate (symmetric) Hausdorff distance with an explicit
// sample count and seed (photogrammetry.md §4.1: CGAL's default sampling density explodes on
// slivers), so every run reports the same number for the same meshes.
#pragma once

#include <cstdint>

#include "photogrammetry/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct HausdorffOptions {
  int64_t samples_per_mesh = 200000;  // random points on the faces of each mesh (plus its vertices)
  uint32_t seed = 1;
};

struct HausdorffDistance {
  double a_to_b_m = 0;   // max over samples of A of the distance to B
  double b_to_a_m = 0;
  double symmetric_m = 0;  // max of the two
};

// Meshes need not be manifold: both are turned into CGAL Surface_meshes through an oriented polygon
// soup (which duplicates non-manifold points, leaving the geometry unchanged). Faces with a repeated
// corner are ignored. Throws InputError if either mesh has no valid face.
HausdorffDistance ApproximateHausdorff(const TriangleMesh& a, const TriangleMesh& b,
                                       const HausdorffOptions& options);

}  // namespace cinepath::photogrammetry
