#include "photogrammetry/mesh/mesh_colors.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

TEST(ColorVerticesFromPoints, VerticesTakeTheColourOfTheirSideOfTheCloud) {
  const PointCloud cloud = testing::TerrainCloud(40, 40, 1.0);  // red-ish east, blue-ish north
  TriangleMesh mesh = testing::TerrainGrid(9, 9, 5.0);
  mesh.colors_rgb.clear();
  ColorVerticesFromPoints(mesh, cloud);
  ASSERT_EQ(mesh.colors_rgb.size(), mesh.num_vertices());
  for (size_t v = 0; v < mesh.num_vertices(); ++v) {
    const auto& p = mesh.vertices_m[v];
    if (std::abs(p.x() - 20) < 3 || std::abs(p.y() - 20) < 3) continue;  // the colour seams
    EXPECT_EQ(mesh.colors_rgb[v][0], p.x() > 20 ? 200 : 20) << p.transpose();
    EXPECT_EQ(mesh.colors_rgb[v][1], 90);
    EXPECT_EQ(mesh.colors_rgb[v][2], p.y() > 20 ? 200 : 20) << p.transpose();
  }
}

TEST(ColorVerticesFromPoints, AnExactHitDominatesTheWeights) {
  PointCloud cloud;
  cloud.positions_m = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  cloud.colors_rgb = {{255, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  TriangleMesh mesh;
  mesh.vertices_m = {{0, 0, 0}};
  ColorVerticesFromPoints(mesh, cloud);
  EXPECT_EQ(mesh.colors_rgb[0][0], 255);
}

TEST(ColorVerticesFromPoints, NeedsColouredPoints) {
  PointCloud cloud;
  cloud.positions_m = {{0, 0, 0}};
  TriangleMesh mesh = testing::TerrainGrid(3, 3, 1.0);
  EXPECT_THROW(ColorVerticesFromPoints(mesh, cloud), InputError);
}

}  // namespace
}  // namespace cinepath::photogrammetry
