#include "photogrammetry/surface/surface_orient.h"

#include <utility>

#include <gtest/gtest.h>

#include "photogrammetry/surface/surface_poisson.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

// Area-weighted mean cosine between each face's normal and the direction up (+z).
double MeanUpCosine(const TriangleMesh& mesh) {
  double sum = 0, area = 0;
  for (const auto& f : mesh.faces) {
    const Eigen::Vector3d n =
        0.5 * (mesh.vertices_m[f[1]] - mesh.vertices_m[f[0]]).cross(mesh.vertices_m[f[2]] - mesh.vertices_m[f[0]]);
    sum += n.z();
    area += n.norm();
  }
  return sum / area;
}

TriangleMesh Flipped(TriangleMesh mesh) {
  for (auto& f : mesh.faces) std::swap(f[1], f[2]);
  return mesh;
}

TEST(OrientTowardCameras, TurnsAnInsideOutTerrainBackToItsCamerasAndLeavesARightOneAlone) {
  const TriangleMesh terrain = testing::TerrainGrid(30, 20, 1.0);
  const PointCloud cloud = testing::TerrainCloud(30, 20, 1.0);  // cameras 50 m above
  ASSERT_GT(MeanUpCosine(terrain), 0.9);

  TriangleMesh right = terrain;
  const OrientReport kept = OrientTowardCameras(&right, cloud);
  EXPECT_EQ(kept.components, 1);
  EXPECT_EQ(kept.components_flipped, 0);
  EXPECT_EQ(kept.faces_flipped, 0);
  EXPECT_EQ(right.faces, terrain.faces);

  TriangleMesh inside_out = Flipped(terrain);
  const OrientReport turned = OrientTowardCameras(&inside_out, cloud);
  EXPECT_EQ(turned.components_flipped, 1);
  EXPECT_EQ(turned.faces_flipped, static_cast<int64_t>(terrain.num_faces()));
  EXPECT_EQ(inside_out.faces, terrain.faces);
}

// Two separate pieces, one inside out: only that one is turned.
TEST(OrientTowardCameras, DecidesPieceByPiece) {
  TriangleMesh a = testing::TerrainGrid(10, 10, 1.0);
  TriangleMesh mesh = a;
  const TriangleMesh b = Flipped(a);
  const uint32_t offset = static_cast<uint32_t>(mesh.num_vertices());
  for (const auto& v : b.vertices_m) mesh.vertices_m.push_back(v + Eigen::Vector3d(40, 0, 0));
  for (const auto& f : b.faces) mesh.faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
  mesh.colors_rgb.clear();
  PointCloud cloud;
  for (const auto& v : mesh.vertices_m) {
    cloud.positions_m.push_back(v);
    cloud.observers.push_back({0});
  }
  cloud.camera_centers_m = {{25, 5, 60}};
  const OrientReport r = OrientTowardCameras(&mesh, cloud);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.components_flipped, 1);
  EXPECT_EQ(r.faces_flipped, static_cast<int64_t>(a.num_faces()));
  EXPECT_GT(MeanUpCosine(mesh), 0.9);
}

// The L (a floor and a wall, cameras in front of the wall): CGAL's Poisson leaves this open surface inside
// out (measured: every piece faces away from the cameras, as on a real facade). Turned, the floor faces
// up and the wall faces the cameras; and the same surface given the other way round comes out the same.
TEST(OrientTowardCameras, APoissonSurfaceFacesItsCamerasWhicheverWayPoissonLeftIt) {
  const PointCloud cloud = testing::LCloud();
  const TriangleMesh poisson = PoissonSurface(cloud, PoissonOptions{}, nullptr);
  ASSERT_GT(poisson.num_faces(), 100u);
  auto floor_and_wall_cosines = [](const TriangleMesh& mesh) {
    double floor = 0, wall = 0;
    for (const auto& f : mesh.faces) {
      const Eigen::Vector3d& a = mesh.vertices_m[f[0]];
      const Eigen::Vector3d n = 0.5 * (mesh.vertices_m[f[1]] - a).cross(mesh.vertices_m[f[2]] - a);
      const Eigen::Vector3d c = (a + mesh.vertices_m[f[1]] + mesh.vertices_m[f[2]]) / 3;
      if (c.z() < 0.2 && c.y() > 1.0) floor += n.z();  // the floor, away from the corner
      if (c.y() < 0.2 && c.z() > 1.0) wall += n.y();   // the wall, above the corner
    }
    return std::make_pair(floor, wall);
  };
  TriangleMesh turned = poisson;
  const OrientReport r = OrientTowardCameras(&turned, cloud);
  const auto [floor, wall] = floor_and_wall_cosines(turned);
  EXPECT_GT(floor, 0);
  EXPECT_GT(wall, 0);
  TriangleMesh other_way = Flipped(poisson);
  const OrientReport r2 = OrientTowardCameras(&other_way, cloud);
  EXPECT_EQ(other_way.faces, turned.faces);
  EXPECT_EQ(r.faces_flipped + r2.faces_flipped, static_cast<int64_t>(poisson.num_faces()));
}

TEST(OrientTowardCameras, WithoutObserversNothingMoves) {
  TriangleMesh mesh = Flipped(testing::TerrainGrid(8, 8, 1.0));
  const TriangleMesh before = mesh;
  PointCloud cloud;
  cloud.positions_m = mesh.vertices_m;
  const OrientReport r = OrientTowardCameras(&mesh, cloud);
  EXPECT_EQ(r.faces_flipped, 0);
  EXPECT_EQ(r.faces_without_observers, static_cast<int64_t>(mesh.num_faces()));
  EXPECT_EQ(mesh.faces, before.faces);
}

}  // namespace
}  // namespace cinepath::photogrammetry
