#include "shots/spline.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::shots {
namespace {

using Eigen::Vector3d;

const std::vector<double> kTimes = {0.0, 1.5, 2.0, 4.0, 7.0};
const std::vector<Vector3d> kPoints = {Vector3d(0, 0, 10), Vector3d(10, 5, 12), Vector3d(14, 12, 15),
                                       Vector3d(5, 25, 20), Vector3d(-10, 30, 18)};

TEST(PathSpline, PassesThroughEveryKeyAtItsTime) {
  for (auto kind : {PathInterpolation::kLinear, PathInterpolation::kCatmullRom, PathInterpolation::kCubicBSpline}) {
    const PathSpline s(kTimes, kPoints, kind);
    for (size_t i = 0; i < kTimes.size(); ++i) {
      EXPECT_LT((s.Position(kTimes[i]) - kPoints[i]).norm(), 1e-9) << PathInterpolationName(kind) << " key " << i;
    }
    // Holds outside the key range.
    EXPECT_LT((s.Position(-5) - kPoints.front()).norm(), 1e-12);
    EXPECT_LT((s.Position(100) - kPoints.back()).norm(), 1e-12);
  }
}

// Left and right one-sided derivatives at each inner key, numerically.
Vector3d LeftDerivative(const PathSpline& s, double t, int order, double h) {
  if (order == 1) return (s.Position(t) - s.Position(t - h)) / h;
  return (s.Position(t) - 2 * s.Position(t - h) + s.Position(t - 2 * h)) / (h * h);
}
Vector3d RightDerivative(const PathSpline& s, double t, int order, double h) {
  if (order == 1) return (s.Position(t + h) - s.Position(t)) / h;
  return (s.Position(t + 2 * h) - 2 * s.Position(t + h) + s.Position(t)) / (h * h);
}

TEST(PathSpline, CatmullRomIsC1InTime) {
  const PathSpline s(kTimes, kPoints, PathInterpolation::kCatmullRom);
  const double h = 1e-6;
  for (size_t i = 1; i + 1 < kTimes.size(); ++i) {
    const Vector3d l = LeftDerivative(s, kTimes[i], 1, h), r = RightDerivative(s, kTimes[i], 1, h);
    EXPECT_LT((l - r).norm(), 1e-3 * std::max(1.0, l.norm())) << "key " << i;
  }
}

// Velocity() itself, at each inner key and just either side of it: the same vector to ~1e-8 relative, and
// the central difference of Position(). Bug 2026-11-29: a difference clamped to the segment turned
// one-sided at a key, off by ~1e-4 relative, and a chase placed from the direction of travel jumped a
// millimetre there (a blend differencing across that jump started at 16 m/s).
TEST(PathSpline, CatmullRomVelocityIsContinuousAtEveryKey) {
  const PathSpline s(kTimes, kPoints, PathInterpolation::kCatmullRom);
  for (size_t i = 1; i + 1 < kTimes.size(); ++i) {
    const Vector3d at = s.Velocity(kTimes[i]);
    const Vector3d before = s.Velocity(std::nextafter(kTimes[i], -1.0));
    const Vector3d after = s.Velocity(std::nextafter(kTimes[i], 100.0));
    const double tol = 1e-8 * at.norm();
    EXPECT_LT((at - before).norm(), tol) << "key " << i;
    EXPECT_LT((at - after).norm(), tol) << "key " << i;
    // Across a key the acceleration jumps (Catmull-Rom is not C2): this difference is off by h/4 times
    // that jump, hence the small h.
    const double h = 1e-7;
    const Vector3d central = (s.Position(kTimes[i] + h) - s.Position(kTimes[i] - h)) / (2 * h);
    EXPECT_LT((at - central).norm(), 1e-5 * at.norm()) << "key " << i;
  }
}

TEST(PathSpline, LinearIsNotC1) {
  // The check above can fail: a linear path has a kink at its inner keys.
  const PathSpline s(kTimes, kPoints, PathInterpolation::kLinear);
  const double h = 1e-6;
  const Vector3d l = LeftDerivative(s, kTimes[1], 1, h), r = RightDerivative(s, kTimes[1], 1, h);
  EXPECT_GT((l - r).norm(), 1.0);
}

TEST(PathSpline, CubicBSplineIsC2InTime) {
  const PathSpline s(kTimes, kPoints, PathInterpolation::kCubicBSpline);
  const double h1 = 1e-6, h2 = 1e-4;
  for (size_t i = 1; i + 1 < kTimes.size(); ++i) {
    const Vector3d l1 = LeftDerivative(s, kTimes[i], 1, h1), r1 = RightDerivative(s, kTimes[i], 1, h1);
    EXPECT_LT((l1 - r1).norm(), 1e-4 * std::max(1.0, l1.norm())) << "key " << i;
    const Vector3d l2 = LeftDerivative(s, kTimes[i], 2, h2), r2 = RightDerivative(s, kTimes[i], 2, h2);
    // One-sided second differences carry O(h) error times the third derivative.
    EXPECT_LT((l2 - r2).norm(), 0.05 * std::max(1.0, l2.norm())) << "key " << i;
  }
  // Catmull-Rom is not C2: its second derivative jumps at some key (the check can fail).
  const PathSpline cr(kTimes, kPoints, PathInterpolation::kCatmullRom);
  double worst = 0;
  for (size_t i = 1; i + 1 < kTimes.size(); ++i) {
    worst = std::max(worst, (LeftDerivative(cr, kTimes[i], 2, h2) - RightDerivative(cr, kTimes[i], 2, h2)).norm());
  }
  EXPECT_GT(worst, 1.0);
}

TEST(PathSpline, VelocityMatchesFiniteDifferences) {
  for (auto kind : {PathInterpolation::kLinear, PathInterpolation::kCatmullRom, PathInterpolation::kCubicBSpline}) {
    const PathSpline s(kTimes, kPoints, kind);
    for (double t = 0.05; t < 6.95; t += 0.173) {
      const Vector3d fd = (s.Position(t + 1e-6) - s.Position(t - 1e-6)) / 2e-6;
      EXPECT_LT((s.Velocity(t) - fd).norm(), 1e-4 * std::max(1.0, fd.norm()))
          << PathInterpolationName(kind) << " t=" << t;
    }
  }
}

TEST(PathSpline, SingleKeyAndBadKeys) {
  const PathSpline one({3.0}, {Vector3d(1, 2, 3)}, PathInterpolation::kCubicBSpline);
  EXPECT_EQ(one.Position(10), Vector3d(1, 2, 3));
  EXPECT_EQ(one.Velocity(3), Vector3d::Zero());
  EXPECT_THROW(PathSpline({0.0, 0.0}, {Vector3d::Zero(), Vector3d::Ones()}, PathInterpolation::kLinear), InputError);
  EXPECT_THROW(PathSpline({}, {}, PathInterpolation::kLinear), InputError);
  // Coincident consecutive keys stay finite.
  const PathSpline still({0.0, 1.0, 2.0}, {Vector3d::Zero(), Vector3d::Zero(), Vector3d::Ones()},
                         PathInterpolation::kCatmullRom);
  EXPECT_TRUE(still.Position(0.5).allFinite());
}

}  // namespace
}  // namespace cinepath::shots
