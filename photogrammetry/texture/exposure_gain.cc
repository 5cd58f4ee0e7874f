#include "photogrammetry/texture/exposure_gain.h"

#include <cmath>

#include <Eigen/Dense>

namespace cinepath::photogrammetry {

ExposureGains FitExposureGains(int num_photos, const std::vector<OverlapSample>& samples,
                               const ExposureGainOptions& options) {
  ExposureGains out;
  out.gain.assign(size_t(num_photos), Eigen::Vector3f::Ones());
  if (num_photos <= 0) return out;
  struct Pair {
    int v, w;
    Eigen::Vector3d cv, cw;
  };
  std::vector<Pair> pairs;
  for (const OverlapSample& s : samples) {
    for (size_t i = 0; i < s.colors.size(); ++i) {
      for (size_t j = i + 1; j < s.colors.size(); ++j) {
        const Eigen::Vector3d cv = s.colors[i].second.cast<double>(), cw = s.colors[j].second.cast<double>();
        bool ok = s.colors[i].first != s.colors[j].first;
        for (int k = 0; k < 3 && ok; ++k) {
          if (cv[k] < options.min_linear || cw[k] < options.min_linear)
            ok = false;
          else if (cv[k] > options.max_ratio * cw[k] || cw[k] > options.max_ratio * cv[k])
            ok = false;
        }
        if (!ok) {
          ++out.pairs_rejected;
          continue;
        }
        pairs.push_back({s.colors[i].first, s.colors[j].first, cv, cw});
      }
    }
  }
  out.pairs_used = int64_t(pairs.size());
  if (pairs.empty()) return out;
  std::vector<bool> used(size_t(num_photos), false);
  for (const Pair& p : pairs) used[size_t(p.v)] = used[size_t(p.w)] = true;
  double sum_before = 0, sum_after = 0;
  for (int k = 0; k < 3; ++k) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(num_photos, num_photos);
    for (const Pair& p : pairs) {
      a(p.v, p.v) += p.cv[k] * p.cv[k];
      a(p.w, p.w) += p.cw[k] * p.cw[k];
      a(p.v, p.w) -= p.cv[k] * p.cw[k];
      a(p.w, p.v) -= p.cv[k] * p.cw[k];
    }
    const double s = a.diagonal().sum() / num_photos;
    const double weight = options.prior * (s > 0 ? s : 1.0);
    a.diagonal().array() += weight;
    const Eigen::VectorXd b = Eigen::VectorXd::Constant(num_photos, weight);
    const Eigen::VectorXd g = a.ldlt().solve(b);
    // The data term is blind to a common scale and the prior pulls every gain toward 0 a little when
    // the overlaps disagree: divide by the geometric mean of the gains of the photos that overlap.
    double log_sum = 0;
    int overlapping = 0;
    for (int v = 0; v < num_photos; ++v) {
      if (used[size_t(v)] && std::isfinite(g[v]) && g[v] > 0) {
        log_sum += std::log(g[v]);
        ++overlapping;
      }
    }
    const double norm = overlapping > 0 ? std::exp(log_sum / overlapping) : 1.0;
    for (int v = 0; v < num_photos; ++v) {
      out.gain[size_t(v)][k] = used[size_t(v)] && std::isfinite(g[v]) && g[v] > 0 ? float(g[v] / norm) : 1.0f;
    }
    for (const Pair& p : pairs) {
      const double before = p.cv[k] - p.cw[k];
      const double after = out.gain[size_t(p.v)][k] * p.cv[k] - out.gain[size_t(p.w)][k] * p.cw[k];
      sum_before += before * before;
      sum_after += after * after;
    }
  }
  out.rms_before = std::sqrt(sum_before / (3.0 * pairs.size()));
  out.rms_after = std::sqrt(sum_after / (3.0 * pairs.size()));
  return out;
}

}  // namespace cinepath::photogrammetry
