// The change `optimize` makes to a plan, as a uniform cubic B-spline in time: a few knots carry the
// variables, and every sample is a fixed weighted sum of four of them. The spline is C2, so adding it
// to a planned path keeps that path's continuity (C1 across continuous transitions, C2 inside a
// shot): docs/optimize.md, "Knots".
//
// Over [t0, t1] with n = max(1, ceil((t1 - t0) / spacing)) segments of length h = (t1 - t0) / n, there
// are n + 3 knots; the segment containing t uses knots seg .. seg + 3 with the basis at u = (t - t0)/h - seg:
//   B0 = (1-u)^3/6, B1 = (3u^3 - 6u^2 + 4)/6, B2 = (-3u^3 + 3u^2 + 3u + 1)/6, B3 = u^3/6,
// and the derivatives in time divide by h, h^2, h^3. A zero-length span has one segment of h = 1 s.
#pragma once

#include <array>

namespace cinepath::optimizer {

struct KnotWeights {
  int first_knot = 0;             // the four knots are first_knot .. first_knot + 3
  std::array<double, 4> value{};  // the spline's value is sum(value[j] * knot[first + j])
  std::array<double, 4> d1{};     // first derivative in time (1/s)
  std::array<double, 4> d2{};     // second (1/s^2)
  std::array<double, 4> d3{};     // third (1/s^3)
};

class KnotSpline {
 public:
  KnotSpline(double t0_s, double t1_s, double spacing_s);
  int num_knots() const { return segments_ + 3; }
  int num_segments() const { return segments_; }
  double segment_s() const { return h_s_; }
  KnotWeights At(double t_s) const;  // t is clamped to [t0, t1]

 private:
  double t0_s_ = 0, t1_s_ = 0, h_s_ = 1;
  int segments_ = 1;
};

}  // namespace cinepath::optimizer
