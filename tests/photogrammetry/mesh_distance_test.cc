#include "photogrammetry/mesh_distance.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace cinepath::photogrammetry
