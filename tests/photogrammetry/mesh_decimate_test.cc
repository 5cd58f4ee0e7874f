#include "photogrammetry/mesh_decimate.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <Eigen/Geometry>

#include "core/error.h"
#include "photogrammetry/mesh_distance.h"
#include "surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

Eigen::AlignedBox3d Bounds(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices_m) box.extend(v);
  return box;
}

class DecimateEveryMethod : public ::testing::TestWithParam<DecimationMethod> {};

TEST_P(DecimateEveryMethod, ReachesTheBudgetKeepsTheBorderAndStaysClose) {
  const TriangleMesh grid = testing::TerrainGrid(101, 101, 1.0);  // 20,000 faces, 100 m square
  DecimateOptions options;
  options.method = GetParam();
  options.target_faces = 2000;
  options.partitions = 4;
  DecimateStats stats;
  const TriangleMesh out = DecimateMesh(grid, options, &stats);
  EXPECT_EQ(stats.faces_in, 20000);
  EXPECT_EQ(stats.faces_out, static_cast<int64_t>(out.num_faces()));
  EXPECT_LE(out.num_faces(), 2600u);
  EXPECT_GE(out.num_faces(), 1200u);
  ASSERT_EQ(out.colors_rgb.size(), out.num_vertices());
  for (const auto& f : out.faces) {
    for (uint32_t i : f) ASSERT_LT(i, out.num_vertices());
  }
  // The outer border stays: the horizontal bounds are those of the input.
  const Eigen::AlignedBox3d in_box = Bounds(grid), out_box = Bounds(out);
  EXPECT_NEAR(out_box.min().x(), in_box.min().x(), 1e-9);
  EXPECT_NEAR(out_box.max().y(), in_box.max().y(), 1e-9);
  // Rolling terrain with 3 m amplitude: a 10 % mesh stays within 0.3 m.
  HausdorffOptions hausdorff;
  hausdorff.samples_per_mesh = 20000;
  EXPECT_LT(ApproximateHausdorff(grid, out, hausdorff).symmetric_m, 0.3);
  // Deterministic.
  EXPECT_EQ(DecimateMesh(grid, options).faces, out.faces);
}

INSTANTIATE_TEST_SUITE_P(Methods, DecimateEveryMethod,
                         ::testing::Values(DecimationMethod::kMeshoptimizer,
                                           DecimationMethod::kMeshoptimizerPartitioned,
                                           DecimationMethod::kCgalGarlandHeckbert,
                                           DecimationMethod::kCgalGarlandHeckbertProbabilistic,
                                           DecimationMethod::kOpenMeshQuadric),
                         [](const auto& info) { return std::string(DecimationMethodName(info.param)); });

TEST(DecimateMesh, ErrorBoundStopsEarlier) {
  const TriangleMesh grid = testing::TerrainGrid(101, 101, 1.0);
  DecimateOptions tight, loose;
  tight.max_error_m = 0.01;
  loose.max_error_m = 0.2;
  DecimateStats tight_stats, loose_stats;
  const TriangleMesh a = DecimateMesh(grid, tight, &tight_stats);
  const TriangleMesh b = DecimateMesh(grid, loose, &loose_stats);
  EXPECT_LT(b.num_faces(), a.num_faces());
  EXPECT_LT(a.num_faces(), grid.num_faces());
  EXPECT_LE(tight_stats.simplifier_error_m, 0.01 * 1.001);
}

TEST(DecimateMesh, NoGoalOrABudgetAboveTheInputKeepsEveryFace) {
  const TriangleMesh grid = testing::TerrainGrid(11, 11, 1.0);
  DecimateOptions options;
  EXPECT_EQ(DecimateMesh(grid, options).num_faces(), grid.num_faces());
  options.target_faces = 1000000;
  EXPECT_EQ(DecimateMesh(grid, options).faces, grid.faces);
}

TEST(DecimationMethod, NamesRoundTrip) {
  EXPECT_EQ(ParseDecimationMethod("openmesh_quadric", "--decimator"), DecimationMethod::kOpenMeshQuadric);
  EXPECT_THROW(ParseDecimationMethod("qslim", "--decimator"), InputError);
}

TEST(DecimateMesh, TiledResultDoesNotDependOnTheThreadCount) {
  const TriangleMesh grid = testing::TerrainGrid(121, 121, 0.5);  // 28,800 faces
  DecimateOptions options;
  options.method = DecimationMethod::kMeshoptimizerPartitioned;
  options.target_faces = 3000;
  const TriangleMesh parallel = DecimateMesh(grid, options);
  TriangleMesh serial;
  {
    tbb::global_control cap(tbb::global_control::max_allowed_parallelism, 1);
    serial = DecimateMesh(grid, options);
  }
  EXPECT_EQ(serial.faces, parallel.faces);
  EXPECT_EQ(serial.vertices_m, parallel.vertices_m);
  EXPECT_LE(parallel.num_faces(), 3300u);
  EXPECT_GE(parallel.num_faces(), 2500u);
}

}  // namespace
}  // namespace cinepath::photogrammetry
