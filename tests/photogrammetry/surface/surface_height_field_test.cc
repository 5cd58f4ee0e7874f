#include "photogrammetry/surface/surface_height_field.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

TEST(HeightFieldSurface, TriangulatesTerrainWithNormalsUpAndVerticesOnIt) {
  const PointCloud cloud = testing::TerrainCloud(40, 30, 1.0);
  HeightFieldReport report;
  const TriangleMesh mesh = HeightFieldSurface(cloud, HeightFieldOptions{}, &report);
  EXPECT_EQ(report.points_in, 1200);
  EXPECT_EQ(report.spikes_removed, 0);
  // A triangulation of n points with h hull points has 2n − 2 − h faces; trimming takes few.
  EXPECT_GT(mesh.num_faces(), 2200u);
  EXPECT_LE(mesh.num_faces(), 2400u);
  ASSERT_EQ(mesh.colors_rgb.size(), mesh.num_vertices());
  for (const auto& f : mesh.faces) {
    const auto& a = mesh.vertices_m[f[0]];
    EXPECT_GT((mesh.vertices_m[f[1]] - a).cross(mesh.vertices_m[f[2]] - a).z(), 0.0);
  }
  for (const auto& v : mesh.vertices_m) {
    EXPECT_NEAR(v.z(), testing::TerrainHeightM(v.x(), v.y()), 1e-12);
  }
}

TEST(HeightFieldSurface, DropsSpikesAndTrimsTrianglesAcrossGaps) {
  PointCloud cloud = testing::TerrainCloud(40, 30, 1.0);
  cloud.positions_m[15 * 40 + 20].z() += 30.0;  // a blunder 30 m up
  cloud.positions_m[5 * 40 + 5].z() -= 12.0;    // and one 12 m down
  // Carve an empty 10 m × 10 m notch out of the east edge: the hull triangles across it are long.
  PointCloud notched;
  for (size_t i = 0; i < cloud.size(); ++i) {
    const auto& p = cloud.positions_m[i];
    if (p.x() > 29 && p.y() > 10 && p.y() < 20) continue;
    notched.positions_m.push_back(p);
  }
  HeightFieldReport report;
  const TriangleMesh mesh = HeightFieldSurface(notched, HeightFieldOptions{}, &report);
  EXPECT_EQ(report.spikes_removed, 2);
  EXPECT_GT(report.long_edge_triangles_trimmed, 0);
  for (const auto& v : mesh.vertices_m) {
    EXPECT_NEAR(v.z(), testing::TerrainHeightM(v.x(), v.y()), 1e-12);
  }
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d c = (mesh.vertices_m[f[0]] + mesh.vertices_m[f[1]] + mesh.vertices_m[f[2]]) / 3.0;
    EXPECT_FALSE(c.x() > 31 && c.y() > 12 && c.y() < 18) << "a triangle spans the notch";
  }
}

TEST(HeightFieldSurface, ThinsLargeCloudsToAboutTheBudget) {
  const PointCloud cloud = testing::TerrainCloud(100, 100, 0.5);
  HeightFieldOptions options;
  options.max_points = 2500;
  HeightFieldReport report;
  const TriangleMesh mesh = HeightFieldSurface(cloud, options, &report);
  EXPECT_GT(report.points_thinned, 6000);
  EXPECT_LT(mesh.num_vertices(), 3000u);
  EXPECT_GT(mesh.num_vertices(), 2000u);
}

TEST(HeightFieldSurface, IsDeterministic) {
  const PointCloud cloud = testing::TerrainCloud(30, 30, 1.0);
  const TriangleMesh a = HeightFieldSurface(cloud, HeightFieldOptions{}, nullptr);
  const TriangleMesh b = HeightFieldSurface(cloud, HeightFieldOptions{}, nullptr);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.vertices_m, b.vertices_m);
}

TEST(HeightFieldSurface, RejectsTooFewOrCollinearPoints) {
  PointCloud two;
  two.positions_m = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(HeightFieldSurface(two, HeightFieldOptions{}, nullptr), InputError);
  PointCloud line;
  for (int i = 0; i < 10; ++i) line.positions_m.emplace_back(i, 2.0 * i, 0.0);
  EXPECT_THROW(HeightFieldSurface(line, HeightFieldOptions{}, nullptr), InputError);
}

}  // namespace
}  // namespace cinepath::photogrammetry
