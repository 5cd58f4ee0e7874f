#include "shots/spline.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace cinepath::shots {

std::string_view PathInterpolationName(PathInterpolation p) {
  switch (p) {
    case PathInterpolation::kLinear: return "linear";
    case PathInterpolation::kCatmullRom: return "catmull_rom";
    case PathInterpolation::kCubicBSpline: return "cubic_bspline";
  }
  return "linear";
}

std::optional<PathInterpolation> PathInterpolationFromName(std::string_view name) {
  if (name == "linear") return PathInterpolation::kLinear;
  if (name == "catmull_rom") return PathInterpolation::kCatmullRom;
  if (name == "cubic_bspline" || name == "bspline") return PathInterpolation::kCubicBSpline;
  return std::nullopt;
}

PathSpline::PathSpline(std::vector<double> times_s, std::vector<Eigen::Vector3d> points, PathInterpolation kind)
    : t_(std::move(times_s)), p_(std::move(points)), kind_(kind) {
  if (t_.empty() || t_.size() != p_.size()) throw InputError("spline: need at least one key, one time per key");
  for (size_t i = 1; i < t_.size(); ++i) {
    if (!(t_[i] > t_[i - 1])) throw InputError("spline: key times must increase strictly");
  }
  const size_t n = t_.size();
  if (n < 2) return;
  if (kind_ == PathInterpolation::kCatmullRom) {
    // Phantom end points by reflection; centripetal knots s_{j+1} = s_j + |P_{j+1} - P_j|^(1/2).
    cr_points_.reserve(n + 2);
    cr_points_.push_back(2.0 * p_[0] - p_[1]);
    for (const auto& q : p_) cr_points_.push_back(q);
    cr_points_.push_back(2.0 * p_[n - 1] - p_[n - 2]);
    cr_knots_.assign(cr_points_.size(), 0.0);
    for (size_t j = 1; j < cr_points_.size(); ++j) {
      const double step = std::sqrt((cr_points_[j] - cr_points_[j - 1]).norm());
      cr_knots_[j] = cr_knots_[j - 1] + std::max(step, 1e-6);  // coincident keys: tiny step, no 0/0
    }
    // Monotone C1 map t -> s through (t_i, s_i) (s_i = cr_knots_[i + 1]): Fritsch-Carlson slopes.
    std::vector<double> secant(n - 1);
    for (size_t i = 0; i + 1 < n; ++i) secant[i] = (cr_knots_[i + 2] - cr_knots_[i + 1]) / (t_[i + 1] - t_[i]);
    knot_slopes_.assign(n, 0.0);
    knot_slopes_[0] = secant[0];
    knot_slopes_[n - 1] = secant[n - 2];
    for (size_t i = 1; i + 1 < n; ++i) {
      // Weighted harmonic mean (Fritsch-Butland), positive since all secants are positive.
      const double h0 = t_[i] - t_[i - 1], h1 = t_[i + 1] - t_[i];
      const double w0 = 2 * h1 + h0, w1 = h1 + 2 * h0;
      knot_slopes_[i] = (w0 + w1) / (w0 / secant[i - 1] + w1 / secant[i]);
    }
  } else if (kind_ == PathInterpolation::kCubicBSpline) {
    // Natural cubic spline: tridiagonal system for the second derivatives m_i (m_0 = m_{n-1} = 0).
    m_.assign(n, Eigen::Vector3d::Zero());
    if (n > 2) {
      std::vector<double> diag(n, 0.0), upper(n, 0.0);
      std::vector<Eigen::Vector3d> rhs(n, Eigen::Vector3d::Zero());
      for (size_t i = 1; i + 1 < n; ++i) {
        const double h0 = t_[i] - t_[i - 1], h1 = t_[i + 1] - t_[i];
        const double lower = h0;
        diag[i] = 2.0 * (h0 + h1);
        upper[i] = h1;
        rhs[i] = 6.0 * ((p_[i + 1] - p_[i]) / h1 - (p_[i] - p_[i - 1]) / h0);
        if (i > 1) {  // Thomas elimination, forward sweep
          const double w = lower / diag[i - 1];
          diag[i] -= w * upper[i - 1];
          rhs[i] -= w * rhs[i - 1];
        }
      }
      for (size_t i = n - 2; i >= 1; --i) {
        m_[i] = (rhs[i] - upper[i] * m_[i + 1]) / diag[i];  // m_[n-1] = 0
        if (i == 1) break;
      }
    }
  }
}

size_t PathSpline::Segment(double time_s) const {
  // Index i with t_i <= t < t_{i+1}, clamped to [0, n-2].
  const auto it = std::upper_bound(t_.begin(), t_.end(), time_s);
  size_t i = it == t_.begin() ? 0 : static_cast<size_t>(it - t_.begin()) - 1;
  return std::min(i, t_.size() - 2);
}

double PathSpline::KnotParameter(size_t i, double time_s, double* ds_dt) const {
  const double h = t_[i + 1] - t_[i];
  const double u = (time_s - t_[i]) / h;
  const double s0 = cr_knots_[i + 1], s1 = cr_knots_[i + 2];
  const double m0 = knot_slopes_[i] * h, m1 = knot_slopes_[i + 1] * h;
  const double u2 = u * u, u3 = u2 * u;
  const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
  if (ds_dt) {
    const double d00 = 6 * u2 - 6 * u, d10 = 3 * u2 - 4 * u + 1, d01 = -6 * u2 + 6 * u, d11 = 3 * u2 - 2 * u;
    *ds_dt = (d00 * s0 + d10 * m0 + d01 * s1 + d11 * m1) / h;
  }
  return h00 * s0 + h10 * m0 + h01 * s1 + h11 * m1;
}

Eigen::Vector3d PathSpline::CatmullRom(size_t i, double s) const {
  // Barry-Goldman pyramid on points j = i .. i+3 of the padded sequence (segment i of the keys).
  const Eigen::Vector3d& p0 = cr_points_[i];
  const Eigen::Vector3d& p1 = cr_points_[i + 1];
  const Eigen::Vector3d& p2 = cr_points_[i + 2];
  const Eigen::Vector3d& p3 = cr_points_[i + 3];
  const double k0 = cr_knots_[i], k1 = cr_knots_[i + 1], k2 = cr_knots_[i + 2], k3 = cr_knots_[i + 3];
  const Eigen::Vector3d a1 = ((k1 - s) * p0 + (s - k0) * p1) / (k1 - k0);
  const Eigen::Vector3d a2 = ((k2 - s) * p1 + (s - k1) * p2) / (k2 - k1);
  const Eigen::Vector3d a3 = ((k3 - s) * p2 + (s - k2) * p3) / (k3 - k2);
  const Eigen::Vector3d b1 = ((k2 - s) * a1 + (s - k0) * a2) / (k2 - k0);
  const Eigen::Vector3d b2 = ((k3 - s) * a2 + (s - k1) * a3) / (k3 - k1);
  return ((k2 - s) * b1 + (s - k1) * b2) / (k2 - k1);
}

Eigen::Vector3d PathSpline::Position(double time_s) const {
  const size_t n = t_.size();
  if (n == 1 || time_s <= t_.front()) return p_.front();
  if (time_s >= t_.back()) return p_.back();
  const size_t i = Segment(time_s);
  const double h = t_[i + 1] - t_[i];
  const double u = (time_s - t_[i]) / h;
  switch (kind_) {
    case PathInterpolation::kLinear: return (1.0 - u) * p_[i] + u * p_[i + 1];
    case PathInterpolation::kCatmullRom: return CatmullRom(i, KnotParameter(i, time_s, nullptr));
    case PathInterpolation::kCubicBSpline: {
      const double a = 1.0 - u;
      return a * p_[i] + u * p_[i + 1] + (h * h / 6.0) * ((a * a * a - a) * m_[i] + (u * u * u - u) * m_[i + 1]);
    }
  }
  return p_[i];
}

Eigen::Vector3d PathSpline::Velocity(double time_s) const {
  const size_t n = t_.size();
  if (n == 1 || time_s < t_.front() || time_s > t_.back()) return Eigen::Vector3d::Zero();
  const size_t i = Segment(time_s);
  const double h = t_[i + 1] - t_[i];
  const double u = (time_s - t_[i]) / h;
  switch (kind_) {
    case PathInterpolation::kLinear: return (p_[i + 1] - p_[i]) / h;
    case PathInterpolation::kCubicBSpline: {
      const double a = 1.0 - u;
      return (p_[i + 1] - p_[i]) / h + (h / 6.0) * (-(3 * a * a - 1) * m_[i] + (3 * u * u - 1) * m_[i + 1]);
    }
    case PathInterpolation::kCatmullRom: {
      // dC/ds by a central difference in s, times ds/dt. C is one cubic per segment, defined past the
      // segment's ends too, so the difference stays central at a key: (C(s+e) - C(s-e)) / 2e = C'(s) +
      // e^2 C'''/6, exact to ~1e-8 relative. A difference clamped to the segment turned one-sided there
      // (error e C''/2): the direction of travel jumped by ~1e-4 rad across each key, a chase or flyby
      // placed from it by a millimetre, and a blend that matched velocities by differencing across that
      // jump started at 16 m/s (bug 2026-11-29: a flyby ending at an actor's key).
      double ds_dt = 0;
      const double s = KnotParameter(i, time_s, &ds_dt);
      const double e = 1e-4 * (cr_knots_[i + 2] - cr_knots_[i + 1]);
      return (CatmullRom(i, s + e) - CatmullRom(i, s - e)) / (2 * e) * ds_dt;
    }
  }
  return Eigen::Vector3d::Zero();
}

}  // namespace cinepath::shots
