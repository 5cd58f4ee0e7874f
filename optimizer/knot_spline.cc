#include "optimizer/knot_spline.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace cinepath::optimizer {

KnotSpline::KnotSpline(double t0_s, double t1_s, double spacing_s) : t0_s_(t0_s), t1_s_(t1_s) {
  CINEPATH_CHECK(spacing_s > 0 && t1_s >= t0_s);
  const double span = t1_s - t0_s;
  segments_ = std::max(1, static_cast<int>(std::ceil(span / spacing_s - 1e-9)));
  h_s_ = span > 0 ? span / segments_ : 1.0;
}

KnotWeights KnotSpline::At(double t_s) const {
  const double x = (std::clamp(t_s, t0_s_, t1_s_) - t0_s_) / h_s_;
  const int seg = std::clamp(static_cast<int>(std::floor(x)), 0, segments_ - 1);
  const double u = x - seg;
  const double h1 = 1.0 / h_s_, h2 = h1 * h1, h3 = h2 * h1;
  KnotWeights w;
  w.first_knot = seg;
  const double v = 1.0 - u;
  w.value = {v * v * v / 6.0, (3 * u * u * u - 6 * u * u + 4) / 6.0, (-3 * u * u * u + 3 * u * u + 3 * u + 1) / 6.0,
             u * u * u / 6.0};
  w.d1 = {-v * v / 2.0 * h1, (3 * u * u - 4 * u) / 2.0 * h1, (-3 * u * u + 2 * u + 1) / 2.0 * h1, u * u / 2.0 * h1};
  w.d2 = {v * h2, (3 * u - 2) * h2, (1 - 3 * u) * h2, u * h2};
  w.d3 = {-h3, 3 * h3, -3 * h3, h3};
  return w;
}

}  // namespace cinepath::optimizer
