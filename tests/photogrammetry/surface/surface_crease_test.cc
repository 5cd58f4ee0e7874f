#include "photogrammetry/surface/surface_crease.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace cinepath::photogrammetry {
namespace {

// Points every 0.5 m (with 2 cm of noise) on a cliff at y = 15 between heights z_low and z_high, and on
// the ground beside it: the plateau (y > 15, z = z_high) when `top`, else the ground at its foot
// (y < 15, z = z_low); 2 m either side of the edge and 2 m along it.
std::vector<Eigen::Vector3d> CliffEdgePoints(bool top, double z_low, double z_high, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Eigen::Vector3d> points;
  for (double x = -2; x <= 2; x += 0.5) {
    for (double t = 0.25; t <= 2; t += 0.5) {
      const double z_face = top ? z_high - t : z_low + t;
      points.emplace_back(x + noise(rng), 15.0 + noise(rng), z_face + noise(rng));
      const double y_ground = top ? 15.0 + t : 15.0 - t;
      points.emplace_back(x + noise(rng), y_ground + noise(rng), (top ? z_high : z_low) + noise(rng));
    }
  }
  return points;
}

CreaseFitOptions Tolerance(double tolerance_m) {
  CreaseFitOptions options;
  options.tolerance_m = tolerance_m;
  return options;
}

TEST(FitCrease, FindsACliffsTopEdgeAndProjectsARoundedVertexOntoTheNearerHalfPlane) {
  const auto points = CliffEdgePoints(true, 3.0, 11.0, 1);
  const CreaseFit fit = FitCrease(points, {0.5, 15.5, 10.8}, Tolerance(0.15), 7);
  ASSERT_EQ(fit.planes, 2) << fit.refused;
  EXPECT_NEAR(fit.angle_deg, 90.0, 2.0);
  EXPECT_GE(fit.points_a + fit.points_b, static_cast<int>(points.size()));
  // Inside the rock, where a smooth surface cuts the corner: onto the plateau (0.2 m up) ...
  EXPECT_LT((NearestOnCrease(fit, {0.5, 15.5, 10.8}) - Eigen::Vector3d(0.5, 15.5, 11.0)).norm(), 0.05);
  // ... or onto the face (0.3 m out).
  EXPECT_LT((NearestOnCrease(fit, {0.5, 15.3, 9.5}) - Eigen::Vector3d(0.5, 15.0, 9.5)).norm(), 0.05);
  // In the air beyond the edge, both feet lie past the edge: the edge itself, not a plane's extension.
  EXPECT_LT((NearestOnCrease(fit, {0.5, 14.8, 11.3}) - Eigen::Vector3d(0.5, 15.0, 11.0)).norm(), 0.05);
}

TEST(FitCrease, FindsACliffsFootAndProjectsAVertexThatFillsTheCorner) {
  const auto points = CliffEdgePoints(false, 3.0, 11.0, 2);
  const CreaseFit fit = FitCrease(points, {-1.0, 14.6, 3.5}, Tolerance(0.15), 7);
  ASSERT_EQ(fit.planes, 2) << fit.refused;
  // In the air in the corner, as a smooth surface fills it: onto the nearer of the face and the ground.
  EXPECT_LT((NearestOnCrease(fit, {-1.0, 14.6, 3.5}) - Eigen::Vector3d(-1.0, 15.0, 3.5)).norm(), 0.05);
  EXPECT_LT((NearestOnCrease(fit, {-1.0, 14.0, 3.3}) - Eigen::Vector3d(-1.0, 14.0, 3.0)).norm(), 0.05);
}

TEST(FitCrease, OnePlaneIsOnePlaneAGentleBendIsNoEdgeAndTooFewPointsAreNothing) {
  std::vector<Eigen::Vector3d> plane, bend;
  for (double x = -2; x <= 2; x += 0.5) {
    for (double y = -2; y <= 2; y += 0.5) {
      plane.emplace_back(x, y, 0.1 * x + 0.01 * std::sin(7 * x * y));
      bend.emplace_back(x, y, y > 0 ? 0.2 * y : 0.0);  // two planes 11° apart: a slope, not an edge
    }
  }
  const Eigen::Vector3d above(0.3, 0.2, 0.5);
  const CreaseFit one = FitCrease(plane, above, Tolerance(0.1), 7);
  ASSERT_EQ(one.planes, 1) << one.refused;
  EXPECT_NEAR(NearestOnCrease(one, above).z(), 0.03, 0.02);
  EXPECT_EQ(FitCrease(bend, above, Tolerance(0.05), 7).planes, 0);
  const auto cliff = CliffEdgePoints(true, 3.0, 11.0, 3);
  EXPECT_EQ(FitCrease({cliff.begin(), cliff.begin() + 10}, above, Tolerance(0.15), 7).planes, 0);
  EXPECT_EQ(FitCrease(cliff, above, Tolerance(0), 7).planes, 0);
}

// A plateau's points and three of the cliff face just below its edge: a least-squares plane tilts toward
// them, the robust plane is the plateau's; unless the query's nearest point is one of the three.
TEST(FitCrease, OnePlaneWithAFewStraysIsThePlaneUnlessTheQueryIsAmongTheStrays) {
  std::vector<Eigen::Vector3d> points;
  for (double x = -2; x <= 2; x += 0.5) {
    for (double y = 15.25; y <= 17; y += 0.5) points.emplace_back(x, y, 11.0);
  }
  for (double x : {-1.0, 0.0, 1.0}) points.emplace_back(x, 15.0, 10.0);
  const CreaseFit fit = FitCrease(points, {0.2, 15.8, 10.5}, Tolerance(0.15), 7);
  ASSERT_EQ(fit.planes, 1) << fit.refused;
  EXPECT_LT((NearestOnCrease(fit, {0.2, 15.8, 10.5}) - Eigen::Vector3d(0.2, 15.8, 11.0)).norm(), 1e-6);
  EXPECT_EQ(FitCrease(points, {0.0, 14.9, 10.0}, Tolerance(0.15), 7).planes, 0);
}

TEST(FitCrease, RefusesPointsThatLieOnNeitherPlaneAndScatteredPoints) {
  // A cliff's edge with a third of its points spread a metre off both planes: not explained.
  auto points = CliffEdgePoints(true, 3.0, 11.0, 4);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (size_t i = 0; i < points.size(); i += 3) points[i] += Eigen::Vector3d(0, 0.5 + 0.5 * u(rng), -1.0);
  const Eigen::Vector3d query(0.5, 15.5, 10.8);
  EXPECT_EQ(FitCrease(points, query, Tolerance(0.15), 7).planes, 0);
  std::vector<Eigen::Vector3d> cloud;
  for (int i = 0; i < 60; ++i) cloud.emplace_back(2 * u(rng), 2 * u(rng), 2 * u(rng));
  EXPECT_EQ(FitCrease(cloud, Eigen::Vector3d::Zero(), Tolerance(0.1), 7).planes, 0);
}

TEST(FitCrease, SameSeedSameFit) {
  const auto points = CliffEdgePoints(false, 0.0, 8.0, 6);
  const Eigen::Vector3d query(0.0, 14.5, 0.5);
  const CreaseFit a = FitCrease(points, query, Tolerance(0.15), 42), b = FitCrease(points, query, Tolerance(0.15), 42);
  ASSERT_EQ(a.planes, 2) << a.refused;
  EXPECT_EQ(a.normal_a, b.normal_a);
  EXPECT_EQ(a.offset_b, b.offset_b);
  EXPECT_EQ(a.points_a, b.points_a);
}

}  // namespace
}  // namespace cinepath::photogrammetry
