#include "photogrammetry/mesh/mesh_distance.h"

#include <algorithm>
#include <cstdio>
#include <utility>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

TEST(ApproximateHausdorff, IdenticalMeshesAreAtZero) {
  const TriangleMesh grid = testing::TerrainGrid(20, 20, 1.0);
  const HausdorffDistance d = ApproximateHausdorff(grid, grid, HausdorffOptions{});
  EXPECT_NEAR(d.symmetric_m, 0.0, 1e-9);
}

TEST(ApproximateHausdorff, ParallelPlanesAreTheirOffsetApart) {
  TriangleMesh a = testing::TerrainGrid(11, 11, 1.0);
  for (auto& v : a.vertices_m) v.z() = 0;
  TriangleMesh b = a;
  for (auto& v : b.vertices_m) v.z() = 0.25;
  const HausdorffDistance d = ApproximateHausdorff(a, b, HausdorffOptions{});
  EXPECT_NEAR(d.a_to_b_m, 0.25, 1e-9);
  EXPECT_NEAR(d.b_to_a_m, 0.25, 1e-9);
  EXPECT_NEAR(d.symmetric_m, 0.25, 1e-9);
}

TEST(ApproximateHausdorff, OneSidedDistancesSeeABump) {
  // A flat plane and the same plane with one vertex lifted by 2 m: B is 2 m from A at the bump,
  // while A is much closer to B everywhere (the bump's flanks come near it).
  TriangleMesh a = testing::TerrainGrid(11, 11, 1.0);
  for (auto& v : a.vertices_m) v.z() = 0;
  TriangleMesh b = a;
  b.vertices_m[5 * 11 + 5].z() = 2.0;
  HausdorffOptions options;
  options.samples_per_mesh = 50000;
  const HausdorffDistance d = ApproximateHausdorff(a, b, options);
  EXPECT_NEAR(d.b_to_a_m, 2.0, 1e-9);  // the vertex itself is a sample
  EXPECT_LT(d.a_to_b_m, 1.0);
  EXPECT_GT(d.a_to_b_m, 0.3);
  EXPECT_DOUBLE_EQ(d.symmetric_m, 2.0);
  // Seeded: the same call gives the same number.
  EXPECT_EQ(ApproximateHausdorff(a, b, options).a_to_b_m, d.a_to_b_m);
}

TEST(ApproximateHausdorff, NonManifoldInputIsAccepted) {
  TriangleMesh a = testing::TerrainGrid(5, 5, 1.0);
  TriangleMesh fin = a;
  fin.vertices_m.emplace_back(1.0, 1.0, 10.0);
  fin.faces.push_back({6, 12, static_cast<uint32_t>(fin.num_vertices() - 1)});  // a third face on an edge
  const HausdorffDistance d = ApproximateHausdorff(a, fin, HausdorffOptions{});
  EXPECT_GT(d.b_to_a_m, 5.0);
  EXPECT_THROW(ApproximateHausdorff(a, TriangleMesh{}, HausdorffOptions{}), InputError);
}

TEST(ApproximateHausdorff, RecordsTheSampleCountAndDoesNotDependOnTheThreadCount) {
  TriangleMesh a = testing::TerrainGrid(60, 50, 1.0);
  TriangleMesh b = a;
  for (size_t i = 0; i < b.num_vertices(); i += 7) b.vertices_m[i].z() += 0.01 * static_cast<double>(i % 13);
  HausdorffOptions options;
  options.samples_per_mesh = 30001;  // not a multiple of anything: every sample is allotted
  const HausdorffDistance d = ApproximateHausdorff(a, b, options);
  EXPECT_EQ(d.samples_a, 30001 + static_cast<int64_t>(a.num_vertices()));
  EXPECT_EQ(d.samples_b, 30001 + static_cast<int64_t>(b.num_vertices()));
  EXPECT_GT(d.symmetric_m, 0.05);
  HausdorffDistance one_thread;
  {
    tbb::global_control cap(tbb::global_control::max_allowed_parallelism, 1);
    one_thread = ApproximateHausdorff(a, b, options);
  }
  EXPECT_EQ(one_thread.a_to_b_m, d.a_to_b_m);  // bit for bit
  EXPECT_EQ(one_thread.b_to_a_m, d.b_to_a_m);
  // Another seed draws other points: a different (but close) one-sided figure without vertices.
  options.sample_vertices = false;
  const HausdorffDistance seed1 = ApproximateHausdorff(a, b, options);
  options.seed = 2;
  const HausdorffDistance seed2 = ApproximateHausdorff(a, b, options);
  EXPECT_EQ(seed1.samples_a, 30001);
  EXPECT_NE(seed1.a_to_b_m, seed2.a_to_b_m);
  EXPECT_NEAR(seed1.a_to_b_m, seed2.a_to_b_m, 0.05);
}

TEST(ApproximateHausdorff, AnIndexIsReusedAcrossMeasurements) {
  const TriangleMesh a = testing::TerrainGrid(30, 30, 1.0);
  TriangleMesh up = a, down = a;
  for (auto& v : up.vertices_m) v.z() += 0.5;
  for (auto& v : down.vertices_m) v.z() -= 0.125;
  const MeshDistanceIndex index(a);
  HausdorffOptions options;
  options.samples_per_mesh = 5000;
  EXPECT_NEAR(ApproximateHausdorff(index, MeshDistanceIndex(up), options).symmetric_m, 0.5, 0.02);
  EXPECT_NEAR(ApproximateHausdorff(index, MeshDistanceIndex(down), options).symmetric_m, 0.125, 0.01);
  EXPECT_EQ(ApproximateHausdorff(index, MeshDistanceIndex(up), options).symmetric_m,
            ApproximateHausdorff(a, up, options).symmetric_m);
  // A point 2 m above a vertex of the flat-ish grid is about 2 m away.
  EXPECT_NEAR(index.DistanceM(a.vertices_m[15 * 30 + 15] + Eigen::Vector3d(0, 0, 2)), 2.0, 0.05);
}

TEST(ApproximateHausdorff, WithoutVertexSamplesTheBumpApexIsApproached) {
  TriangleMesh a = testing::TerrainGrid(11, 11, 1.0);
  for (auto& v : a.vertices_m) v.z() = 0;
  TriangleMesh b = a;
  b.vertices_m[5 * 11 + 5].z() = 2.0;
  HausdorffOptions options;
  options.samples_per_mesh = 50000;
  options.sample_vertices = false;
  const HausdorffDistance d = ApproximateHausdorff(a, b, options);
  EXPECT_LT(d.b_to_a_m, 2.0);
  EXPECT_GT(d.b_to_a_m, 1.5);
}

TEST(BoundDistanceTo, ParallelPlanesGiveTheOffsetWithinTheTolerance) {
  TriangleMesh a = testing::TerrainGrid(11, 11, 1.0);
  for (auto& v : a.vertices_m) v.z() = 0;
  TriangleMesh b = testing::TerrainGrid(4, 4, 10.0 / 3.0);  // coarser triangles over the same square
  for (auto& v : b.vertices_m) v.z() = 0.25;
  const MeshDistanceIndex ia(a, "A"), ib(b, "B");
  for (const auto& [from, to] : {std::pair{&ia, &ib}, std::pair{&ib, &ia}}) {
    const HausdorffInterval bound = from->BoundDistanceTo(*to, 0.0, HausdorffBoundOptions{});
    EXPECT_NEAR(bound.lower_m, 0.25, 1e-9);
    // Refinement stops once the bound is within the tolerance (here 2 % of 0.25 m).
    EXPECT_GE(bound.upper_m, 0.25 - 1e-9);
    EXPECT_LE(bound.upper_m, 0.25 + 0.02 * 0.25 + 1e-9);
    EXPECT_EQ(bound.unresolved_triangles, 0);
  }
}

TEST(BoundDistanceTo, BracketsTheTrueDistanceWhereSamplingFallsShort) {
  // A: a plane of two large triangles. B: a fine grid of the same plane with one vertex lifted by
  // 2 m. A's farthest point from B lies under the bump, inside a face of A (not at a vertex of A):
  // few samples miss it, the bound must not.
  TriangleMesh a;
  a.vertices_m = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  a.faces = {{0, 1, 2}, {0, 2, 3}};
  TriangleMesh b = testing::TerrainGrid(11, 11, 1.0);
  for (auto& v : b.vertices_m) v.z() = 0;
  b.vertices_m[4 * 11 + 6].z() = 2.0;  // the bump at (6, 4), inside face {0, 1, 2} of A
  const MeshDistanceIndex ia(a, "A"), ib(b, "B");
  HausdorffOptions few;
  few.samples_per_mesh = 20;
  const double sampled = ia.MaxDistanceTo(ib, few);
  HausdorffBoundOptions deep;
  deep.max_depth = 10;  // A's triangles are 10 m across: pieces down to 1 cm near the bump
  const HausdorffInterval bound = ia.BoundDistanceTo(ib, sampled, deep);
  HausdorffOptions dense;
  dense.samples_per_mesh = 400000;
  const double dense_estimate = ia.MaxDistanceTo(ib, dense);
  std::printf("A->B: 20 samples %.4f m, 400 k samples %.4f m, bound [%.4f, %.4f] m\n", sampled, dense_estimate,
              bound.lower_m, bound.upper_m);
  EXPECT_GE(bound.lower_m, sampled);
  EXPECT_LE(bound.lower_m, bound.upper_m);
  EXPECT_LE(dense_estimate, bound.upper_m + 1e-12);  // no point of A is beyond the upper bound
  EXPECT_EQ(bound.unresolved_triangles, 0);
  EXPECT_LE(bound.upper_m - bound.lower_m, std::max(0.001, 0.02 * bound.lower_m) + 1e-12);
  EXPECT_GT(bound.lower_m, sampled + 0.05);  // the bound found what 20 samples missed
  // B -> A: the bump's apex is a vertex of B, 2 m above A.
  const HausdorffInterval back = ib.BoundDistanceTo(ia, 0.0, HausdorffBoundOptions{});
  EXPECT_NEAR(back.lower_m, 2.0, 1e-9);
  EXPECT_NEAR(back.upper_m, 2.0, 1e-9);
  // The same at one thread.
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const HausdorffInterval serial = ia.BoundDistanceTo(ib, sampled, deep);
  EXPECT_EQ(serial.lower_m, bound.lower_m);
  EXPECT_EQ(serial.upper_m, bound.upper_m);
}

}  // namespace
}  // namespace cinepath::photogrammetry
