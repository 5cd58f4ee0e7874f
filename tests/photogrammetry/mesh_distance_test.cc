#include "photogrammetry/mesh_distance.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "surface_test_meshes.h"

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

}  // namespace
}  // namespace cinepath::photogrammetry
