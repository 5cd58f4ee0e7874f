#include "photogrammetry/surface/surface_crease.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "photogrammetry/surface/vertex_moves_internal.h"

namespace cinepath::photogrammetry {
namespace {

struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0;
  double Distance(const Eigen::Vector3d& x) const { return normal.dot(x) - offset; }
};

// splitmix64: a small, fast generator whose sequence depends on the seed alone.
uint64_t NextRandom(uint64_t& state) {
  uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::vector<uint32_t> Within(const std::vector<Eigen::Vector3d>& points, const std::vector<uint32_t>& among,
                             const Plane& plane, double tolerance_m) {
  std::vector<uint32_t> in;
  for (uint32_t i : among) {
    if (std::abs(plane.Distance(points[i])) <= tolerance_m) in.push_back(i);
  }
  return in;
}

// The plane through the most of `among` (within the tolerance), from `trials` samples of three of them,
// then refitted by least squares to its points twice. False when no sample spans a plane.
bool BestPlane(const std::vector<Eigen::Vector3d>& points, const std::vector<uint32_t>& among,
               const CreaseFitOptions& options, uint64_t& rng, Plane* best, std::vector<uint32_t>* on_best) {
  const size_t n = among.size();
  if (n < 3) return false;
  size_t best_count = 0;
  for (int trial = 0; trial < options.trials; ++trial) {
    const Eigen::Vector3d& a = points[among[NextRandom(rng) % n]];
    const Eigen::Vector3d& b = points[among[NextRandom(rng) % n]];
    const Eigen::Vector3d& c = points[among[NextRandom(rng) % n]];
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double longest2 = std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
    if (!(cross.norm() > 0.1 * longest2)) continue;  // three points nearly on a line span no reliable plane
    Plane plane{cross.normalized(), 0};
    plane.offset = plane.normal.dot(a);
    size_t count = 0;
    for (uint32_t i : among) count += std::abs(plane.Distance(points[i])) <= options.tolerance_m;
    if (count > best_count) {
      best_count = count;
      *best = plane;
    }
  }
  if (best_count < 3) return false;
  for (int refit = 0; refit < 2; ++refit) {
    const std::vector<uint32_t> in = Within(points, among, *best, options.tolerance_m);
    std::vector<Eigen::Vector3d> q;
    q.reserve(in.size());
    for (uint32_t i : in) q.push_back(points[i]);
    const internal::FittedPlane fitted = internal::FitPlane(q);
    if (!fitted.valid) break;
    best->normal = fitted.normal;
    best->offset = fitted.normal.dot(fitted.centroid);
  }
  *on_best = Within(points, among, *best, options.tolerance_m);
  return on_best->size() >= 3;
}

// The side of `other` on which the points of `own` lie, away from the edge (farther than the tolerance
// from `other`): ±1, or 0 when too few points are off the edge or they do not agree.
double SideOf(const std::vector<Eigen::Vector3d>& points, const std::vector<uint32_t>& own, const Plane& other,
              const CreaseFitOptions& options) {
  int positive = 0, negative = 0;
  for (uint32_t i : own) {
    const double d = other.Distance(points[i]);
    if (d > options.tolerance_m) ++positive;
    if (d < -options.tolerance_m) ++negative;
  }
  const int off = positive + negative;
  if (off < 3) return 0;
  if (positive >= options.min_side_agreement * off) return 1;
  if (negative >= options.min_side_agreement * off) return -1;
  return 0;
}

}  // namespace

CreaseFit FitCrease(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& query,
                    const CreaseFitOptions& options, uint64_t seed) {
  CreaseFit fit;
  const auto n = static_cast<uint32_t>(points.size());
  const auto min_points = static_cast<size_t>(options.min_points_per_plane);
  if (!(options.tolerance_m > 0) || n < 2 * min_points) return fit.Refused("too few points");
  uint64_t rng = seed;
  std::vector<uint32_t> all(n);
  for (uint32_t i = 0; i < n; ++i) all[i] = i;
  Plane a, b;
  std::vector<uint32_t> on_a, on_b;
  if (!BestPlane(points, all, options, rng, &a, &on_a)) return fit.Refused("no plane");
  fit.normal_a = a.normal;
  fit.offset_a = a.offset;
  fit.points_a = static_cast<int>(on_a.size());
  std::vector<uint32_t> rest;
  for (uint32_t i : all) {
    if (std::abs(a.Distance(points[i])) > options.tolerance_m) rest.push_back(i);
  }
  if (rest.size() < min_points) {
    // One plane and a few strays (too few to carry a second plane): the plane, when it carries most of
    // the points and the point nearest to the query (the query belongs to its surface, not the strays').
    uint32_t nearest = 0;
    for (uint32_t i = 1; i < n; ++i) {
      if ((points[i] - query).squaredNorm() < (points[nearest] - query).squaredNorm()) nearest = i;
    }
    if (on_a.size() < options.min_share_one_plane * n) return fit.Refused("one plane carries too few points");
    if (!(std::abs(a.Distance(points[nearest])) <= options.tolerance_m)) return fit.Refused("nearest point a stray");
    fit.planes = 1;
    return fit;
  }
  if (!BestPlane(points, rest, options, rng, &b, &on_b)) return fit.Refused("no second plane");
  on_b = Within(points, all, b, options.tolerance_m);
  if (on_a.size() < min_points || on_b.size() < min_points) return fit.Refused("a plane carries too few points");
  uint32_t explained = 0;
  for (const auto& p : points) {
    explained += std::abs(a.Distance(p)) <= options.tolerance_m || std::abs(b.Distance(p)) <= options.tolerance_m;
  }
  if (explained < options.min_share_explained * n) return fit.Refused("points on neither plane");
  const double angle_deg = std::acos(std::min(1.0, std::abs(a.normal.dot(b.normal)))) * 180.0 / M_PI;
  if (angle_deg < options.min_angle_deg) return fit.Refused("planes too close in angle");
  const double side_a = SideOf(points, on_a, b, options), side_b = SideOf(points, on_b, a, options);
  if (side_a == 0 || side_b == 0) return fit.Refused("points on both sides of the other plane");
  fit.planes = 2;
  fit.normal_b = b.normal;
  fit.offset_b = b.offset;
  fit.side_a_of_b = side_a;
  fit.side_b_of_a = side_b;
  fit.points_b = static_cast<int>(on_b.size());
  fit.angle_deg = angle_deg;
  return fit;
}

Eigen::Vector3d NearestOnCrease(const CreaseFit& fit, const Eigen::Vector3d& query) {
  const Plane a{fit.normal_a, fit.offset_a}, b{fit.normal_b, fit.offset_b};
  if (fit.planes == 1) return query - a.Distance(query) * a.normal;
  // The edge: the line where the planes meet, and the point of it nearest to the query.
  const Eigen::Vector3d u = a.normal.cross(b.normal);
  const Eigen::Vector3d on_line = (a.offset * b.normal.cross(u) + b.offset * u.cross(a.normal)) / u.squaredNorm();
  const Eigen::Vector3d along = u.normalized();
  const Eigen::Vector3d on_edge = on_line + (query - on_line).dot(along) * along;
  auto on_half_plane = [&](const Plane& own, const Plane& other, double side) -> Eigen::Vector3d {
    const Eigen::Vector3d foot = query - own.Distance(query) * own.normal;
    return other.Distance(foot) * side >= 0 ? foot : on_edge;
  };
  const Eigen::Vector3d x_a = on_half_plane(a, b, fit.side_a_of_b), x_b = on_half_plane(b, a, fit.side_b_of_a);
  return (x_a - query).squaredNorm() <= (x_b - query).squaredNorm() ? x_a : x_b;
}

}  // namespace cinepath::photogrammetry
