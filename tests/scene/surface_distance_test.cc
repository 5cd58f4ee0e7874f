#include "scene/surface_distance.h"

#include <gtest/gtest.h>

namespace cinepath::scene {
namespace {

using Eigen::Vector3d;

// A ground quad of side 2 s at height 0, counter-clockwise seen from above (its front faces up); with
// `both_windings` each triangle is also there clockwise, as double-sided exports carry it.
SceneMesh GroundQuad(double s, bool both_windings) {
  SceneMesh m;
  m.positions_enu_m = {{-s, -s, 0}, {s, -s, 0}, {s, s, 0}, {-s, s, 0}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  if (both_windings) {
    // Twins first and last, so that neither winding comes first for every face.
    m.faces = {{0, 2, 1}, {0, 1, 2}, {0, 2, 3}, {0, 3, 2}};
  }
  return m;
}

TEST(SurfaceDistance, OneWindingGroundIsASolidsTop) {
  const SurfaceDistance d(GroundQuad(50, false));
  const auto above = d.Closest(Vector3d(1, 2, 3));
  ASSERT_TRUE(above);
  EXPECT_NEAR(above->distance_m, 3.0, 1e-12);
  EXPECT_FALSE(above->behind);
  EXPECT_TRUE(above->normal_enu.isApprox(Vector3d::UnitZ(), 1e-12));
  const auto below = d.Closest(Vector3d(1, 2, -3));
  EXPECT_TRUE(below->behind);  // under a lone ground quad is inside
}

TEST(SurfaceDistance, DoubleSidedGroundNeverFlipsInsideAndOutside) {
  const SurfaceDistance d(GroundQuad(50, true));
  for (const Vector3d p : {Vector3d(1, 2, 3), Vector3d(-20, 7, 0.5), Vector3d(3, -30, 10)}) {
    const auto c = d.Closest(p);
    ASSERT_TRUE(c);
    EXPECT_NEAR(c->distance_m, p.z(), 1e-12);
    EXPECT_FALSE(c->behind) << p.transpose();
    EXPECT_TRUE(c->normal_enu.isApprox(Vector3d::UnitZ(), 1e-12)) << p.transpose();  // towards the point
  }
  // Under a sheet the normal points down, towards the point: no side of it is inside.
  const auto under = d.Closest(Vector3d(1, 2, -3));
  EXPECT_FALSE(under->behind);
  EXPECT_TRUE(under->normal_enu.isApprox(-Vector3d::UnitZ(), 1e-12));
}

}  // namespace
}  // namespace cinepath::scene
