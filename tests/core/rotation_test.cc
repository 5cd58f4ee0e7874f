#include "core/rotation.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/angles.h"
#include "core/error.h"

namespace cinepath {
namespace {

using Eigen::Quaterniond;
using Eigen::Vector3d;

Quaterniond AxisAngle(double angle_rad, const Vector3d& axis) {
  return Quaterniond(Eigen::AngleAxisd(angle_rad, axis.normalized()));
}

TEST(Slerp, ExactAtTheEndsAndUnitNorm) {
  const Quaterniond a = AxisAngle(0.3, Vector3d(1, 2, 3));
  const Quaterniond b = AxisAngle(2.1, Vector3d(-1, 0.5, 0.2));
  EXPECT_EQ(Slerp(a, b, 0.0).coeffs(), a.normalized().coeffs());
  const Quaterniond end = Slerp(a, b, 1.0);
  EXPECT_NEAR(AngleBetweenRad(end, b), 0.0, 1e-15);
  for (int i = 0; i <= 100; ++i) {
    EXPECT_NEAR(Slerp(a, b, i / 100.0).norm(), 1.0, 1e-15);
  }
}

TEST(Slerp, ConstantAngularSpeedOnTheShortArc) {
  const Quaterniond a = Quaterniond::Identity();
  const Quaterniond b = AxisAngle(RadFromDeg(100), Vector3d::UnitZ());
  // Give b the sign that would take the long way round: slerp must still take the short arc.
  const Quaterniond b_flipped(-b.w(), -b.x(), -b.y(), -b.z());
  for (int i = 0; i <= 10; ++i) {
    const double t = i / 10.0;
    const Quaterniond q = Slerp(a, b_flipped, t);
    EXPECT_NEAR(AngleBetweenRad(a, q), RadFromDeg(100) * t, 1e-12);
    EXPECT_NEAR(AngleBetweenRad(q, b), RadFromDeg(100) * (1 - t), 1e-12);
  }
}

TEST(Slerp, IdenticalQuaternionsStayPut) {
  const Quaterniond a = AxisAngle(1.0, Vector3d(0, 1, 1));
  for (double t : {0.0, 0.25, 0.5, 1.0}) {
    const Quaterniond q = Slerp(a, a, t);
    EXPECT_NEAR(AngleBetweenRad(q, a), 0.0, 1e-15);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  }
}

TEST(Slerp, AntipodalQuaternionsAreTheSameRotation) {
  const Quaterniond a = AxisAngle(1.0, Vector3d(0, 1, 1));
  const Quaterniond minus_a(-a.w(), -a.x(), -a.y(), -a.z());
  for (double t : {0.0, 0.3, 0.5, 0.7, 1.0}) {
    const Quaterniond q = Slerp(a, minus_a, t);
    EXPECT_TRUE(std::isfinite(q.w()));
    EXPECT_NEAR(AngleBetweenRad(q, a), 0.0, 1e-15) << t;
  }
}

TEST(Slerp, RotationsHalfATurnApart) {
  // Identity and 180 deg about z: the quaternion dot product is 0; halfway is 90 deg about z.
  const Quaterniond half_turn = AxisAngle(kPi, Vector3d::UnitZ());
  const Quaterniond mid = Slerp(Quaterniond::Identity(), half_turn, 0.5);
  EXPECT_NEAR(AngleBetweenRad(mid, AxisAngle(kPi / 2, Vector3d::UnitZ())), 0.0, 1e-15);
  EXPECT_NEAR(mid.norm(), 1.0, 1e-15);
}

TEST(Slerp, ZeroQuaternionIsACleanError) {
  EXPECT_THROW(Slerp(Quaterniond(0, 0, 0, 0), Quaterniond::Identity(), 0.5), InputError);
}

TEST(Squad, InterpolatesKeysAndIsC1AtInnerKeys) {
  std::vector<Quaterniond> keys = {AxisAngle(0.0, Vector3d::UnitZ()), AxisAngle(0.6, Vector3d(0, 1, 0.3)),
                                   AxisAngle(1.4, Vector3d(1, 1, 0)), AxisAngle(1.9, Vector3d(0, 0, 1))};
  const auto q = AlignHemispheres(keys);
  const auto s = SquadControlPoints(q);
  for (size_t i = 0; i + 1 < q.size(); ++i) {
    EXPECT_NEAR(AngleBetweenRad(Squad(q[i], q[i + 1], s[i], s[i + 1], 0.0), q[i]), 0.0, 1e-15);
    EXPECT_NEAR(AngleBetweenRad(Squad(q[i], q[i + 1], s[i], s[i + 1], 1.0), q[i + 1]), 0.0, 1e-15);
  }
  // Angular velocity just before and just after each inner key (unit parameter spacing).
  const double h = 1e-5;
  for (size_t i = 1; i + 1 < q.size(); ++i) {
    const Quaterniond before = Squad(q[i - 1], q[i], s[i - 1], s[i], 1.0 - h);
    const Quaterniond after = Squad(q[i], q[i + 1], s[i], s[i + 1], h);
    const Vector3d w_in = 2.0 * QuaternionLog(before.conjugate() * q[i]) / h;
    const Vector3d w_out = 2.0 * QuaternionLog(q[i].conjugate() * after) / h;
    EXPECT_LT((w_in - w_out).norm(), 1e-3 * std::max(1.0, w_in.norm())) << "key " << i;
  }
}

TEST(LookAt, ForwardAxisHitsTargetWithLevelHorizon) {
  const Vector3d dir(3, -4, -2);
  const Quaterniond q = LookAt(dir);
  EXPECT_NEAR((q * Vector3d::UnitZ() - dir.normalized()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((q * Vector3d::UnitX()).z(), 0.0, 1e-15);  // camera x horizontal
  EXPECT_GT((q * -Vector3d::UnitY()).z(), 0.0);          // image top points upward
}

TEST(LookAt, StraightDownFollowsTheFallbackHeading) {
  // Straight down, heading north: image top points north, right points east.
  const Quaterniond north = LookAt(Vector3d(0, 0, -1), 0.0);
  EXPECT_NEAR((north * Vector3d::UnitZ() - Vector3d(0, 0, -1)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((north * -Vector3d::UnitY() - Vector3d(0, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((north * Vector3d::UnitX() - Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
  // Heading east: image top points east.
  const Quaterniond east = LookAt(Vector3d(0, 0, -5), 90.0);
  EXPECT_NEAR((east * -Vector3d::UnitY() - Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
  // Continuous with a nearly vertical view facing the same heading.
  const Quaterniond almost = LookAt(Vector3d(0, 1e-6, -1), 0.0);
  EXPECT_LT(AngleBetweenRad(almost, north), 2e-6);
  // Straight up, heading north: image top points south.
  const Quaterniond up = LookAt(Vector3d(0, 0, 2), 0.0);
  EXPECT_NEAR((up * -Vector3d::UnitY() - Vector3d(0, -1, 0)).norm(), 0.0, 1e-15);
  EXPECT_THROW(LookAt(Vector3d::Zero()), InputError);
  EXPECT_THROW(LookAt(Vector3d(std::nan(""), 0, 0)), InputError);
}

TEST(AimWithScreenOffset, PlacesTheTargetOnTheRequestedRay) {
  const Vector3d target(10, 25, -8);
  const Vector3d ray(-0.2, 0.1, 1.0);  // left of and below the centre
  const Quaterniond q = AimWithScreenOffset(target, ray);
  EXPECT_NEAR((q * ray.normalized() - target.normalized()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((q * Vector3d::UnitX()).z(), 0.0, 1e-12);
  // A centred ray is the plain look-at.
  EXPECT_LT(AngleBetweenRad(AimWithScreenOffset(target, Vector3d::UnitZ()), LookAt(target)), 1e-12);
}

TEST(Gimbal, KnownAnswers) {
  // Heading north, level: the camera looks north.
  GimbalAngles g;
  g.drone_heading_deg = 0;
  Quaterniond q = WorldFromCameraFromGimbal(g);
  EXPECT_NEAR((q * Vector3d::UnitZ() - Vector3d(0, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((q * Vector3d::UnitX() - Vector3d(1, 0, 0)).norm(), 0.0, 1e-15);
  // Heading 90 (east), pitch -30: looks east and down.
  g.drone_heading_deg = 90;
  g.gimbal_pitch_deg = -30;
  q = WorldFromCameraFromGimbal(g);
  EXPECT_NEAR((q * Vector3d::UnitZ() - Vector3d(std::cos(RadFromDeg(30)), 0, -0.5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(CameraHeadingDeg(q), 90.0, 1e-12);
  // Roll +10: the image's right side goes down.
  g = GimbalAngles{0, 0, 10, 0};
  q = WorldFromCameraFromGimbal(g);
  EXPECT_NEAR((q * Vector3d::UnitX()).z(), -std::sin(RadFromDeg(10)), 1e-15);
}

TEST(Gimbal, RoundTrips) {
  for (double heading : {0.0, 45.0, 179.0, 270.0, 359.5}) {
    for (double pitch : {-89.0, -45.0, 0.0, 20.0}) {
      for (double roll : {-5.0, 0.0, 12.0}) {
        const GimbalAngles in{heading, pitch, roll, 0.0};
        const GimbalAngles out = GimbalFromWorldFromCamera(WorldFromCameraFromGimbal(in));
        EXPECT_NEAR(AngleDiffDeg(out.drone_heading_deg, heading), 0.0, 1e-9);
        EXPECT_NEAR(out.gimbal_pitch_deg, pitch, 1e-9);
        EXPECT_NEAR(out.gimbal_roll_deg, roll, 1e-9);
        EXPECT_EQ(out.gimbal_yaw_deg, 0.0);
      }
    }
  }
  // With the drone's heading fixed, the gimbal yaw takes the difference.
  const GimbalAngles out = GimbalFromWorldFromCamera(WorldFromCameraFromGimbal(GimbalAngles{10, -20, 0, 0}), 350.0);
  EXPECT_NEAR(out.drone_heading_deg, 350.0, 1e-12);
  EXPECT_NEAR(out.gimbal_yaw_deg, 20.0, 1e-9);
}

TEST(Gimbal, StraightDownMatchesTheLookAtRule) {
  for (double heading : {0.0, 30.0, 200.0}) {
    const Quaterniond nadir = LookAt(Vector3d(0, 0, -1), heading);
    const GimbalAngles g = GimbalFromWorldFromCamera(nadir);
    EXPECT_NEAR(g.gimbal_pitch_deg, -90.0, 1e-9);
    EXPECT_NEAR(g.gimbal_roll_deg, 0.0, 1e-9);
    EXPECT_NEAR(AngleDiffDeg(g.drone_heading_deg, heading), 0.0, 1e-9);
    EXPECT_LT(AngleBetweenRad(WorldFromCameraFromGimbal(g), nadir), 1e-9);
  }
}

}  // namespace
}  // namespace cinepath
