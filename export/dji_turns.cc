#include "export/dji_turns.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace cinepath::exporter {

namespace {

constexpr int kArcChords = 32;       // even: the arc's midpoint is a vertex
constexpr double kMaxTurnDeg = 179;  // sharper reversals stop at the waypoint
constexpr double kDampingShrink = 0.7;
constexpr double kLegShare = 0.45;  // d ≤ 0.45 × each adjacent leg: the two on a leg sum to < its length

double PointSegmentDistance(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len_sq = ab.squaredNorm();
  const double t = len_sq > 1e-18 ? std::clamp((q - a).dot(ab) / len_sq, 0.0, 1.0) : 0.0;
  return (q - (a + t * ab)).norm();
}

// The turn at corner w as a polyline from A (on the incoming leg) to B (on the outgoing leg); a single
// point (the corner) when d = 0 or the corner is an end of the path.
std::vector<Eigen::Vector3d> TurnPolyline(const std::vector<Eigen::Vector3d>& corners,
                                          const std::vector<double>& damping_m, size_t w) {
  const Eigen::Vector3d& p = corners[w];
  if (damping_m[w] <= 0 || w == 0 || w + 1 >= corners.size()) return {p};
  const Eigen::Vector3d in = p - corners[w - 1];
  const Eigen::Vector3d out = corners[w + 1] - p;
  if (in.norm() < 1e-9 || out.norm() < 1e-9) return {p};
  const Eigen::Vector3d u_in = in.normalized();
  const Eigen::Vector3d u_out = out.normalized();
  const double d = damping_m[w];
  const Eigen::Vector3d a = p - d * u_in;
  const Eigen::Vector3d b = p + d * u_out;
  const double delta = std::acos(std::clamp(u_in.dot(u_out), -1.0, 1.0));
  if (delta < 1e-6) return {a, b};  // straight on: the "arc" is the segment
  // Centre on the bisector, |PC| = r / cos(δ/2), r = d / tan(δ/2).
  const double r = d / std::tan(delta / 2);
  const Eigen::Vector3d bisector = (u_out - u_in).normalized();
  const Eigen::Vector3d c = p + bisector * (r / std::cos(delta / 2));
  const Eigen::Vector3d e1 = (a - c).normalized();
  Eigen::Vector3d e2 = (b - c) - (b - c).dot(e1) * e1;
  e2.normalize();
  std::vector<Eigen::Vector3d> arc;
  for (int k = 0; k <= kArcChords; ++k) {
    const double theta = delta * k / kArcChords;
    arc.push_back(c + r * (std::cos(theta) * e1 + std::sin(theta) * e2));
  }
  arc.front() = a;
  arc.back() = b;
  return arc;
}

double PolylineDistance(const std::vector<Eigen::Vector3d>& line, const Eigen::Vector3d& q) {
  if (line.size() == 1) return (q - line.front()).norm();
  double best = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k + 1 < line.size(); ++k) best = std::min(best, PointSegmentDistance(q, line[k], line[k + 1]));
  return best;
}

}  // namespace

double DistanceToTurnPath(const std::vector<Eigen::Vector3d>& corners, const std::vector<double>& damping_m, size_t w,
                          const Eigen::Vector3d& q) {
  CINEPATH_CHECK(corners.size() == damping_m.size() && w + 1 < corners.size());
  const std::vector<Eigen::Vector3d> turn_a = TurnPolyline(corners, damping_m, w);
  const std::vector<Eigen::Vector3d> turn_b = TurnPolyline(corners, damping_m, w + 1);
  // Straight piece: from the end of turn w to the start of turn w + 1.
  const double straight = PointSegmentDistance(q, turn_a.back(), turn_b.front());
  return std::min({straight, PolylineDistance(turn_a, q), PolylineDistance(turn_b, q)});
}

double TurnPathDeviation(const std::vector<TrajectorySample>& samples, const std::vector<int>& waypoints,
                         const std::vector<double>& damping_m) {
  std::vector<Eigen::Vector3d> corners;
  for (int i : waypoints) corners.push_back(samples[i].position_enu_m);
  double worst = 0;
  for (size_t w = 0; w + 1 < waypoints.size(); ++w) {
    for (int k = waypoints[w]; k <= waypoints[w + 1]; ++k) {
      worst = std::max(worst, DistanceToTurnPath(corners, damping_m, w, samples[k].position_enu_m));
    }
  }
  return worst;
}

TurnFit FitCoordinatedTurns(const std::vector<TrajectorySample>& samples, const std::vector<int>& waypoints,
                            const std::vector<bool>& must_stop, double max_deviation_m) {
  CINEPATH_CHECK(must_stop.size() == waypoints.size());
  const size_t n = waypoints.size();
  TurnFit fit;
  fit.damping_m.assign(n, 0.0);
  std::vector<Eigen::Vector3d> corners;
  for (int i : waypoints) corners.push_back(samples[i].position_enu_m);

  // Largest deviation over the samples of the legs touching waypoint w (the next turn still 0).
  auto local_deviation = [&](size_t w) {
    double worst = 0;
    for (size_t leg : {w - 1, w}) {
      for (int k = waypoints[leg]; k <= waypoints[leg + 1]; ++k) {
        worst = std::max(worst, DistanceToTurnPath(corners, fit.damping_m, leg, samples[k].position_enu_m));
      }
    }
    return worst;
  };
  for (size_t w = 1; w + 1 < n; ++w) {
    if (must_stop[w]) continue;
    const double len_in = (corners[w] - corners[w - 1]).norm();
    const double len_out = (corners[w + 1] - corners[w]).norm();
    const Eigen::Vector3d u_in = (corners[w] - corners[w - 1]) / std::max(len_in, 1e-12);
    const Eigen::Vector3d u_out = (corners[w + 1] - corners[w]) / std::max(len_out, 1e-12);
    const double turn_deg = std::acos(std::clamp(u_in.dot(u_out), -1.0, 1.0)) * 180.0 / M_PI;
    if (turn_deg > kMaxTurnDeg) continue;
    for (double d = kLegShare * std::min(len_in, len_out); d >= kDjiMinDampingM; d *= kDampingShrink) {
      fit.damping_m[w] = std::floor(d * 100) / 100;  // written with 2 decimals: model what is written
      if (local_deviation(w) <= max_deviation_m) break;
      fit.damping_m[w] = 0;
    }
  }
  fit.max_deviation_m = TurnPathDeviation(samples, waypoints, fit.damping_m);
  return fit;
}

}  // namespace cinepath::exporter
