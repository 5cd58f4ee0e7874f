#include "scene/ray_caster.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::scene {
namespace {

using Eigen::Vector3d;

// A square of side 2 s at height z, centred on (cx, cy), counter-clockwise seen from above.
void AddSquare(SceneMesh& m, double cx, double cy, double z, double s) {
  const uint32_t b = static_cast<uint32_t>(m.positions_enu_m.size());
  m.positions_enu_m.insert(m.positions_enu_m.end(),
                           {{cx - s, cy - s, z}, {cx + s, cy - s, z}, {cx + s, cy + s, z}, {cx - s, cy + s, z}});
  m.faces.push_back({b, b + 1, b + 2});
  m.faces.push_back({b, b + 2, b + 3});
}

TEST(RayCaster, HitsTheClosestSurfaceWithItsNormalAndFace) {
  SceneMesh m;
  AddSquare(m, 0, 0, 0, 50);  // ground, faces 0-1
  AddSquare(m, 0, 0, 10, 5);  // a roof at 10 m, faces 2-3
  const RayCaster rc(m);
  const auto hit = rc.Intersect(Vector3d(1, 2, 100), Vector3d(0, 0, -3));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->distance_m, 90.0, 1e-9);
  EXPECT_TRUE(hit->position_enu_m.isApprox(Vector3d(1, 2, 10), 1e-12));
  EXPECT_GE(hit->face, 2u);
  EXPECT_TRUE(hit->normal_enu.isApprox(Vector3d::UnitZ()));
  // Beside the roof the ground is hit.
  EXPECT_NEAR(rc.Intersect(Vector3d(20, 0, 100), -Vector3d::UnitZ())->distance_m, 100.0, 1e-9);
  // Looking up from below the ground: nothing above the roof.
  EXPECT_FALSE(rc.Intersect(Vector3d(20, 0, 50), Vector3d::UnitZ()));
  // A maximum distance short of the surface misses it.
  EXPECT_FALSE(rc.Intersect(Vector3d(20, 0, 100), -Vector3d::UnitZ(), 0, 99.0));
}

// Packets of eight (and of fewer) rays give each ray the hit Intersect gives it: a fan of rays from one
// point over a ground and a roof, some missing everything, none through an edge.
TEST(RayCaster, PacketsOfEightHitWhatSingleRaysHit) {
  SceneMesh m;
  AddSquare(m, 0, 0, 0, 50);
  AddSquare(m, 3.3, -2.1, 10, 5);
  const RayCaster rc(m);
  const Vector3d origin(0.37, 0.21, 30);
  for (int count = 1; count <= 8; ++count) {
    for (int row = 0; row < 20; ++row) {
      Vector3d origins[8], directions[8];
      for (int i = 0; i < count; ++i) {
        origins[i] = origin;
        directions[i] = Vector3d(0.13 * (i - 3.5) + 0.011 * row, 0.09 * (row - 10) + 0.003 * i, -1).normalized();
      }
      std::optional<RayHit> hits[8];
      rc.Intersect8(origins, directions, count, hits);
      for (int i = 0; i < count; ++i) {
        const auto single = rc.Intersect(origins[i], directions[i]);
        ASSERT_EQ(single.has_value(), hits[i].has_value()) << count << " " << row << " " << i;
        if (!single) continue;
        EXPECT_EQ(single->face, hits[i]->face);
        EXPECT_EQ(single->distance_m, hits[i]->distance_m);
        EXPECT_EQ(single->u, hits[i]->u);
        EXPECT_EQ(single->v, hits[i]->v);
      }
    }
  }
  // Rays that miss everything (pointing up) and a bad count.
  Vector3d up[2] = {Vector3d::UnitZ(), Vector3d(0.1, 0, 1).normalized()}, at[2] = {origin, origin};
  std::optional<RayHit> none[2];
  rc.Intersect8(at, up, 2, none);
  EXPECT_FALSE(none[0] || none[1]);
  EXPECT_THROW(rc.Intersect8(at, up, 9, none), InternalError);
}

TEST(RayCaster, OcclusionAndTheHighestSurfaceBelow) {
  SceneMesh m;
  AddSquare(m, 0, 0, 0, 50);
  AddSquare(m, 0, 0, 10, 5);
  const RayCaster rc(m);
  // A line of sight over the roof is clear; through it, blocked.
  EXPECT_FALSE(rc.Occluded(Vector3d(-20, 0, 12), Vector3d(1, 0, 0), 0, 40));
  EXPECT_TRUE(rc.Occluded(Vector3d(0, 0, 20), Vector3d(0, 0, -1), 0, 15));
  EXPECT_FALSE(rc.Occluded(Vector3d(0, 0, 20), Vector3d(0, 0, -1), 0, 9.5));
  EXPECT_NEAR(rc.SurfaceBelow(1, 1)->position_enu_m.z(), 10.0, 1e-12);      // the roof
  EXPECT_NEAR(rc.SurfaceBelow(1, 1, 5.0)->position_enu_m.z(), 0.0, 1e-12);  // under the roof: the ground
  EXPECT_FALSE(rc.SurfaceBelow(100, 0));                                    // off the mesh
}

TEST(RayCaster, FarFromTheOriginKeepsMillimetres) {
  // A ground square 10 km east of the origin, slightly tilted: hits stay exact to well under a mm.
  SceneMesh m;
  m.positions_enu_m = {{9990, -10, 0.0}, {10010, -10, 0.2}, {10010, 10, 0.2}, {9990, 10, 0.0}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  const RayCaster rc(m);
  for (double e = 9991; e < 10010; e += 1.37) {
    const auto hit = rc.SurfaceBelow(e, 3.3);
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->position_enu_m.z(), 0.01 * (e - 9990), 1e-6) << e;
  }
}

TEST(RayCaster, ThroughAnEdgeStillHits) {
  SceneMesh m;
  AddSquare(m, 0, 0, 0, 1);  // the diagonal (0,0)-(1,1) is a shared edge
  const RayCaster rc(m);
  EXPECT_TRUE(rc.SurfaceBelow(0.25, 0.25));
  EXPECT_TRUE(rc.SurfaceBelow(0.0, 0.0));
}

// The low-quality build (Embree's Morton builder, for a large mesh that answers few rays) gives every ray the hit
// the high-quality build gives it: a wavy terrain of 20,000 triangles under a fan of rays, a few missing it. The
// high-quality build keeps each face's normal; the low one computes it at each hit: the same bits.
TEST(RayCaster, TheLowQualityBuildHitsWhatTheHighQualityBuildHits) {
  SceneMesh m;
  const int n = 101;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double e = i - 50.0, north = j - 50.0;
      m.positions_enu_m.emplace_back(e, north, 3 * std::sin(0.21 * e) * std::cos(0.17 * north));
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const uint32_t a = j * n + i;
      m.faces.push_back({a, a + 1, a + n + 1});
      m.faces.push_back({a, a + n + 1, a + n});
    }
  }
  const RayCaster high(m), low(m, RayCaster::BuildQuality::kLow);
  int hits = 0, misses = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vector3d origin(0.31 * (k % 37) - 5.7, 0.23 * (k % 41) - 4.1, 12 + 0.01 * k);
    const Vector3d direction(std::cos(0.013 * k), std::sin(0.017 * k), -0.15 - 0.0004 * k);
    const auto a = high.Intersect(origin, direction), b = low.Intersect(origin, direction);
    ASSERT_EQ(a.has_value(), b.has_value()) << "ray " << k;
    if (!a) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_EQ(a->face, b->face) << "ray " << k;
    EXPECT_EQ(a->distance_m, b->distance_m) << "ray " << k;
    EXPECT_EQ(a->normal_enu, b->normal_enu) << "ray " << k;
    EXPECT_EQ(a->position_enu_m, b->position_enu_m) << "ray " << k;
    EXPECT_NEAR(a->normal_enu.norm(), 1.0, 1e-12) << "ray " << k;
  }
  EXPECT_GT(hits, 1000);
  EXPECT_GT(misses, 0);
}

TEST(RayCaster, RefusesAnEmptyMesh) { EXPECT_THROW(RayCaster{SceneMesh{}}, InputError); }

}  // namespace
}  // namespace cinepath::scene
