#include "core/angles.h"

#include <cmath>

#include <gtest/gtest.h>

namespace cinepath {
namespace {

TEST(Angles, Normalization) {
  EXPECT_EQ(NormalizeDeg180(190), -170);
  EXPECT_EQ(NormalizeDeg180(-190), 170);
  EXPECT_EQ(NormalizeDeg180(720), 0);
  EXPECT_FALSE(std::signbit(NormalizeDeg180(-360)));
  EXPECT_EQ(NormalizeDeg180Open(-180), 180);
  EXPECT_EQ(NormalizeDeg180Open(540), 180);
  EXPECT_EQ(NormalizeDeg360(-90), 270);
  EXPECT_EQ(NormalizeDeg360(360), 0);
  EXPECT_LT(NormalizeDeg360(-1e-15), 360.0);
  EXPECT_NEAR(NormalizeRadPi(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(NormalizeRadPi(-kPi), kPi, 1e-12);
  EXPECT_EQ(AngleDiffDeg(350, 10), 20);
  EXPECT_EQ(AngleDiffDeg(10, 350), -20);
}

TEST(Angles, CompassHeadingFromEnuYaw) {
  // East (ENU yaw 0) is compass 90; north (yaw +90) is compass 0; west 270; south 180.
  EXPECT_NEAR(HeadingDegFromEnuYaw(0), 90, 1e-12);
  EXPECT_NEAR(HeadingDegFromEnuYaw(kPi / 2), 0, 1e-12);
  EXPECT_NEAR(HeadingDegFromEnuYaw(kPi), 270, 1e-12);
  EXPECT_NEAR(HeadingDegFromEnuYaw(-kPi / 2), 180, 1e-12);
  for (double h : {0.0, 45.0, 135.0, 359.5}) {
    EXPECT_NEAR(HeadingDegFromEnuYaw(EnuYawFromHeadingDeg(h)), h, 1e-9);
  }
}

}  // namespace
}  // namespace cinepath
