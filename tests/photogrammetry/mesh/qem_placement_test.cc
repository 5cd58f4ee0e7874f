#include "photogrammetry/mesh/qem_placement.h"

#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace cinepath::photogrammetry::internal {
namespace {

// The shapes a collapse meets: a curved patch (full rank), a plane (one direction pinned), a crease
// (two), a noisy plane (nearly one).
enum class Shape { kCurved, kFlat, kCrease, kNoisyFlat };

struct Edge {
  Quadric qa, qb;
  Eigen::Vector3d a, b;
};

// An edge of length ~scale at ~100 × scale from the origin, each end with 3-8 area-weighted planes of
// `shape` through points near it.
Edge RandomEdge(Shape shape, std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  const double scale = std::exp(3 * g(rng));
  Edge e;
  e.a = Eigen::Vector3d(g(rng), g(rng), g(rng)) * 100 * scale;
  e.b = e.a + Eigen::Vector3d(g(rng), g(rng), 0.1 * g(rng)) * scale;
  for (int side = 0; side < 2; ++side) {
    Quadric& q = side ? e.qb : e.qa;
    const Eigen::Vector3d& at = side ? e.b : e.a;
    const int planes = 3 + static_cast<int>(u(rng) * 6);
    for (int k = 0; k < planes; ++k) {
      Eigen::Vector3d n(0, 0, 1);
      if (shape == Shape::kCurved) n = Eigen::Vector3d(g(rng), g(rng), 2 + g(rng));
      if (shape == Shape::kCrease && k % 2 == 0) n = Eigen::Vector3d(1, 0, 0);
      if (shape == Shape::kNoisyFlat) n = Eigen::Vector3d(1e-3 * g(rng), 1e-3 * g(rng), 1);
      n.normalize();
      const Eigen::Vector3d on = at + Eigen::Vector3d(g(rng), g(rng), g(rng)) * 0.01 * scale;
      q.AddPlane(n, -n.dot(on), u(rng) * scale * scale);
    }
  }
  return e;
}

using Place4 = int (*)(const Lanes4&, double, double, std::array<double, 4>&, bool);

// The share of the lanes `place` prices on edges of `shape`, after checking that every lane it prices is
// Placement's error bit for bit, on both paths (which agree on which lanes they price).
double PricedShare(Place4 place, Shape shape) {
  const double reach = 2.0, rcond = 1e-3;  // QemOptions' defaults
  std::mt19937_64 rng(11 + static_cast<int>(shape));
  {
    int lanes = 0, priced = 0, mismatched = 0;
    for (int batch = 0; batch < 20000; ++batch) {
      std::array<Edge, 4> edges;
      Lanes4 in;
      for (int k = 0; k < 4; ++k) {
        edges[k] = RandomEdge(shape, rng);
        in.qa[k] = &edges[k].qa, in.qb[k] = &edges[k].qb, in.a[k] = &edges[k].a, in.b[k] = &edges[k].b;
      }
      std::array<double, 4> portable{}, wide{};
      const int done = place(in, reach, rcond, portable, false);
      if (CpuHasAvx2()) {
        EXPECT_EQ(place(in, reach, rcond, wide, true), done);
      } else {
        wide = portable;
      }
      for (int k = 0; k < 4; ++k) {
        ++lanes;
        if (!(done >> k & 1)) continue;
        ++priced;
        const double expected = Placement(Sum(edges[k].qa, edges[k].qb), edges[k].a, edges[k].b, reach, rcond).error;
        mismatched += std::memcmp(&expected, &portable[k], sizeof(double)) != 0 ? 1 : 0;
        mismatched += std::memcmp(&expected, &wide[k], sizeof(double)) != 0 ? 1 : 0;
      }
    }
    EXPECT_EQ(mismatched, 0) << static_cast<int>(shape);
    return static_cast<double>(priced) / lanes;
  }
}

// PlaceFullRank4 prices nearly every full-rank edge, and no edge of a plane (one direction pinned:
// Placement truncates): what it leaves, PlaceAny4 or Placement does.
TEST(PlaceFullRank4, IsPlacementBitForBitWhereItPrices) {
  EXPECT_GT(PricedShare(PlaceFullRank4, Shape::kCurved), 0.95);
  EXPECT_EQ(PricedShare(PlaceFullRank4, Shape::kFlat), 0.0);
  PricedShare(PlaceFullRank4, Shape::kCrease);
  PricedShare(PlaceFullRank4, Shape::kNoisyFlat);
}

// PlaceAny4 prices nearly every edge of every shape, the truncated solves and the points out of reach
// included; Placement asks Eigen's closed form for the rest.
TEST(PlaceAny4, IsPlacementBitForBitWhereItPrices) {
  for (const Shape shape : {Shape::kCurved, Shape::kFlat, Shape::kCrease, Shape::kNoisyFlat}) {
    EXPECT_GT(PricedShare(PlaceAny4, shape), 0.95) << static_cast<int>(shape);
  }
}

}  // namespace
}  // namespace cinepath::photogrammetry::internal
