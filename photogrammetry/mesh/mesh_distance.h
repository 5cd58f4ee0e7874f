// Distances between meshes: an approximate symmetric Hausdorff distance with an explicit sample
// count and seed (CGAL's default sampling density explodes on slivers), so
// every run reports the same number for the same meshes, at any thread count.
//
// Samples on a mesh: optionally its vertices, plus `samples_per_mesh` points on its faces, spread
// by area. The faces are cut into fixed chunks (by face index, never by thread); each chunk gets its
// share of the samples in proportion to its area and draws them with its own seed (derived from
// `seed` and the chunk index). Each sample's distance to the other mesh is an exact closest-point
// query in a CGAL AABB tree; the maximum over the samples is the one-sided distance. Chunks run in
// parallel (TBB); the result does not depend on the scheduling. Within a chunk, a sample whose
// distance to the triangle nearest the previous sample is already within the chunk's maximum is
// not queried (it cannot raise the maximum): the result is the same, most queries are skipped.
#pragma once

#include <cstdint>
#include <memory>

#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct HausdorffOptions {
  int64_t samples_per_mesh = 200000;  // random points on the faces of each mesh
  bool sample_vertices = true;        // also every vertex of each mesh
  uint32_t seed = 1;
};

// The one-sided distance sup_{x on A} d(x, B) between two bounds (MeshDistanceIndex::BoundDistanceTo).
struct HausdorffBoundOptions {
  double tolerance_m = 0.001;        // stop refining a triangle once its bound is within this of the lower bound
  double relative_tolerance = 0.02;  // ... or within this fraction of the lower bound
  int max_depth = 6;                 // at most this many 1-to-4 subdivisions of a face
};

struct HausdorffInterval {
  double lower_m = 0;  // a distance actually reached (at a vertex or a subdivision point of A)
  double upper_m = 0;  // no point of A is farther than this from B
  int64_t points_measured = 0;
  int64_t unresolved_triangles = 0;  // pieces left at max_depth with their bound above the tolerance
};

struct HausdorffDistance {
  double a_to_b_m = 0;  // max over the samples of A of the distance to B
  double b_to_a_m = 0;
  double symmetric_m = 0;  // max of the two
  int64_t samples_a = 0;   // how many samples were measured on A (vertices + face samples)
  int64_t samples_b = 0;
};

// A mesh with its AABB tree, built once and reused for several measurements (the pipeline measures
// every decimation candidate against the same input). Keeps a reference to `mesh`: the mesh must
// outlive the index. Faces with a repeated corner or an index out of range are ignored; the mesh
// need not be manifold or oriented. Throws InputError when no valid face is left.
class MeshDistanceIndex {
 public:
  explicit MeshDistanceIndex(const TriangleMesh& mesh, const char* name = "A");
  ~MeshDistanceIndex();
  MeshDistanceIndex(const MeshDistanceIndex&) = delete;
  MeshDistanceIndex& operator=(const MeshDistanceIndex&) = delete;

  // Max over the samples of `this` mesh of the distance to `other` (one-sided).
  double MaxDistanceTo(const MeshDistanceIndex& other, const HausdorffOptions& options,
                       int64_t* samples = nullptr) const;
  // Bounds the one-sided distance from every point of `this` mesh (not only samples) to `other`.
  // Each face is checked whole: the distance to one triangle of `other` is a convex function, so
  // its maximum over a (sub-)triangle is at a corner, and max over the corners of the distance to
  // any single triangle of `other` bounds the distance from the whole piece to `other`; so does
  // max over the corners of their distance to `other` plus the largest distance from a point of
  // the piece to its nearest corner (the distance to a set is 1-Lipschitz). Pieces whose bound is
  // above the running lower bound (+ tolerance) are cut in four, to max_depth. `known_lower_m`: a
  // distance already found (e.g. by MaxDistanceTo). Deterministic at any thread count.
  HausdorffInterval BoundDistanceTo(const MeshDistanceIndex& other, double known_lower_m,
                                    const HausdorffBoundOptions& options) const;
  // Total area of the valid faces (m²).
  double AreaM2() const;
  // Distance from a point to the mesh.
  double DistanceM(const Eigen::Vector3d& point) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

HausdorffDistance ApproximateHausdorff(const MeshDistanceIndex& a, const MeshDistanceIndex& b,
                                       const HausdorffOptions& options);
// Convenience: builds both indexes. Throws InputError if either mesh has no valid face.
HausdorffDistance ApproximateHausdorff(const TriangleMesh& a, const TriangleMesh& b, const HausdorffOptions& options);

}  // namespace cinepath::photogrammetry
