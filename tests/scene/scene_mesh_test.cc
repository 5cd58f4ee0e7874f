#include "scene/scene_mesh.h"

#include <gtest/gtest.h>

namespace cinepath::scene {
namespace {

SceneMesh TwoTriangles() {
  SceneMesh m;
  m.positions_enu_m = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {10, 10, 0}, {11, 10, 0}, {10, 11, 0}};
  m.faces = {{0, 1, 2}, {3, 4, 5}};
  m.colors_linear = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  return m;
}

TEST(SceneMesh, BoundsCoverTheUsedVertices) {
  const SceneMesh m = TwoTriangles();
  EXPECT_TRUE(m.Bounds().min().isApprox(Eigen::Vector3d(0, 0, 0)));
  EXPECT_TRUE(m.Bounds().max().isApprox(Eigen::Vector3d(11, 11, 0)));
  EXPECT_TRUE(SceneMesh().Bounds().isEmpty());
}

TEST(SceneMesh, CropKeepsTheFacesMeetingTheBoxAndRenumbers) {
  const SceneMesh m = TwoTriangles();
  const SceneMesh c = CropToBox(m, Eigen::AlignedBox3d(Eigen::Vector3d(9, 9, -1), Eigen::Vector3d(20, 20, 1)));
  ASSERT_EQ(c.num_faces(), 1u);
  ASSERT_EQ(c.num_vertices(), 3u);
  EXPECT_EQ(c.faces[0], (std::array<uint32_t, 3>{0, 1, 2}));
  EXPECT_TRUE(c.positions_enu_m[0].isApprox(Eigen::Vector3d(10, 10, 0)));
  EXPECT_TRUE(c.colors_linear[0].isApprox(Eigen::Vector3f(0, 1, 0)));
  // A box that meets nothing gives an empty mesh.
  EXPECT_EQ(CropToBox(m, Eigen::AlignedBox3d(Eigen::Vector3d(50, 50, 50), Eigen::Vector3d(60, 60, 60))).num_faces(),
            0u);
}

}  // namespace
}  // namespace cinepath::scene
