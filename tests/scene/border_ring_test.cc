#include "scene/border_ring.h"

#include <cmath>

#include <gtest/gtest.h>

namespace cinepath::scene {
namespace {

// An n x n grid of 1 m cells (two triangles each) centred on the origin, its outer ring of cells at height
// `edge_up_m` and the rest at 0, with the cells inside `hole_radius_m` of the centre left out (a hole).
SceneMesh Grid(int n, double edge_up_m, double hole_radius_m) {
  SceneMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const bool edge = i == 0 || j == 0 || i == n || j == n;
      m.positions_enu_m.emplace_back(i - n / 2.0, j - n / 2.0, edge ? edge_up_m : 0.0);
    }
  }
  auto at = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (std::hypot(i + 0.5 - n / 2.0, j + 0.5 - n / 2.0) < hole_radius_m) continue;
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return m;
}

TEST(BorderRing, KeepsTheOuterEdgeNotAHoleInside) {
  const SceneMesh m = Grid(40, 2.0, 6.0);
  const BorderRing ring = FindBorderRing(m);
  ASSERT_FALSE(ring.faces.empty());
  EXPECT_NEAR(ring.centre_m.norm(), 0.0, 1e-9);  // symmetric
  // Every kept face lies on the outer edge (its centroid within 1 m of the grid's border, 20 m out)...
  for (uint32_t f : ring.faces) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (uint32_t v : m.faces[f]) c += m.positions_enu_m[v] / 3;
    EXPECT_GT(std::max(std::abs(c.x()), std::abs(c.y())), 19.0) << "face " << f;
  }
  // ...so the plane is at the edge's height, though the hole's border (at 0) has about as many edges.
  EXPECT_DOUBLE_EQ(ring.height_m, 2.0);
  EXPECT_GT(ring.radius_m, 19.0);
  ASSERT_EQ(ring.sectors.size(), ring.faces.size());
  for (int s : ring.sectors) EXPECT_TRUE(s >= 0 && s < BorderRing::kSectors);
}

TEST(BorderRing, ClosedMeshStandsAtItsLowestVertex) {
  SceneMesh tetra;
  tetra.positions_enu_m = {{0, 0, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetra.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const BorderRing ring = FindBorderRing(tetra);
  EXPECT_DOUBLE_EQ(ring.height_m, -1.0);
  EXPECT_FALSE(ring.faces.empty());
  EXPECT_TRUE(FindBorderRing(SceneMesh()).faces.empty());
}

TEST(BorderRing, SectorsOfAzimuth) {
  EXPECT_EQ(SectorOf({1, 0}), BorderRing::kSectors / 2);      // east: 0 deg of atan2, the middle sector
  EXPECT_EQ(SectorOf({-1, -1e-9}), 0);                        // just south of west: -180 deg
  EXPECT_EQ(SectorOf({0, 1}), 3 * BorderRing::kSectors / 4);  // north
}

TEST(BorderRing, SectorColoursFillGapsAndChangeGently) {
  BorderRing ring;
  ring.faces = {0, 1};
  ring.sectors = {0, 36};
  const Eigen::Vector3f red(1, 0, 0), blue(0, 0, 1), grey(0.5f, 0.5f, 0.5f);
  Eigen::Vector3f mean;
  const std::vector<Eigen::Vector3f> colors = SectorColors(ring, {red, blue}, grey, &mean);
  ASSERT_EQ(colors.size(), size_t(BorderRing::kSectors));
  EXPECT_TRUE(mean.isApprox(Eigen::Vector3f(0.5f, 0, 0.5f)));
  // Sector 0 stays mostly red, 36 mostly blue; half-way (18, 54) an even mix; neighbours differ by little.
  EXPECT_GT(colors[0].x(), 0.8f);
  EXPECT_GT(colors[36].z(), 0.8f);
  EXPECT_NEAR(colors[18].x(), 0.5f, 1e-5f);
  EXPECT_NEAR(colors[54].z(), 0.5f, 1e-5f);
  for (int k = 0; k < BorderRing::kSectors; ++k) {
    EXPECT_LT((colors[size_t(k)] - colors[size_t((k + 1) % BorderRing::kSectors)]).norm(), 0.06f) << k;
  }
  // No face at all: the fallback everywhere.
  for (const auto& c : SectorColors(BorderRing{}, {}, grey)) EXPECT_TRUE(c.isApprox(grey));
}

}  // namespace
}  // namespace cinepath::scene
