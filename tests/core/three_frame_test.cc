#include "core/three_frame.h"

#include <cmath>

#include <gtest/gtest.h>

namespace cinepath {
namespace {

// world_from_camera for a camera looking along `forward` (ENU) with `right` its x axis (y = down).
Eigen::Quaterniond LookingAlong(const Eigen::Vector3d& forward, const Eigen::Vector3d& right) {
  Eigen::Matrix3d m;
  m.col(0) = right;
  m.col(1) = forward.cross(right);  // z x x = y (down)
  m.col(2) = forward;
  return Eigen::Quaterniond(m);
}

TEST(ThreeFrame, EnuToYUp) {
  // east stays x, up becomes y, north becomes -z (what the GLB stores, so three.js shows it upright)
  EXPECT_EQ(ThreeFromEnu({1, 2, 3}), Eigen::Vector3d(1, 3, -2));
}

TEST(ThreeFrame, EnuFromThreeUndoesItExactly) {
  for (const Eigen::Vector3d enu :
       {Eigen::Vector3d(1.5, 2.5, 3.5), Eigen::Vector3d(-1e7, 0.1, -0.0), Eigen::Vector3d(3e-9, -7, 1e5)}) {
    EXPECT_EQ(EnuFromThree(ThreeFromEnu(enu)), enu);
    EXPECT_EQ(ThreeFromEnu(EnuFromThree(enu)), enu);
  }
  EXPECT_EQ(EnuFromThree({1, 3, -2}), Eigen::Vector3d(1, 2, 3));
}

TEST(ThreeFrame, LevelCameraLookingNorth) {
  const Eigen::Quaterniond q = ThreeCameraFromWorldFromCamera(LookingAlong({0, 1, 0}, {1, 0, 0}));
  // A three.js camera looks along its -Z, with +Y up on the screen and +X right.
  EXPECT_TRUE((q * Eigen::Vector3d(0, 0, -1)).isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));  // north
  EXPECT_TRUE((q * Eigen::Vector3d(0, 1, 0)).isApprox(Eigen::Vector3d(0, 1, 0), 1e-12));    // sky up
  EXPECT_TRUE((q * Eigen::Vector3d(1, 0, 0)).isApprox(Eigen::Vector3d(1, 0, 0), 1e-12));    // east right
}

TEST(ThreeFrame, CameraLookingStraightDownWithNorthUp) {
  // Forward = down, image x = east, so image y (down) = south and the picture's top is north.
  const Eigen::Quaterniond q = ThreeCameraFromWorldFromCamera(LookingAlong({0, 0, -1}, {1, 0, 0}));
  EXPECT_TRUE((q * Eigen::Vector3d(0, 0, -1)).isApprox(Eigen::Vector3d(0, -1, 0), 1e-12));  // looks down
  EXPECT_TRUE((q * Eigen::Vector3d(0, 1, 0)).isApprox(Eigen::Vector3d(0, 0, -1), 1e-12));   // top = north
  EXPECT_GE(q.w(), 0);
}

TEST(ThreeFrame, VerticalFieldOfViewFollowsTheSensorFit) {
  CameraSpec camera;  // Super 35, 24.89 mm wide, 3840 x 2160: the image uses 14.00 mm of the height
  const double expected = 2 * std::atan(24.89 * 2160.0 / 3840.0 / (2 * 35.0)) * 180 / M_PI;
  EXPECT_NEAR(VerticalFieldOfViewDeg(camera, 35.0), expected, 1e-9);
}

}  // namespace
}  // namespace cinepath
