#include "photogrammetry/georef/georeference.h"

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include "core/error.h"
#include "core/number_format.h"

namespace cinepath::photogrammetry {
namespace {

Similarity3 FitSubset(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                      const std::vector<int>& indices) {
  Eigen::Matrix3Xd src(3, indices.size()), dst(3, indices.size());
  for (size_t k = 0; k < indices.size(); ++k) {
    src.col(k) = source[indices[k]];
    dst.col(k) = target[indices[k]];
  }
  return Similarity3::FromMatrix(Eigen::umeyama(src, dst, true));
}

bool IsUsable(const Similarity3& t) {
  return std::isfinite(t.scale) && t.scale > 0 && t.translation.allFinite() && t.rotation.coeffs().allFinite();
}

double TriangleArea(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

}  // namespace

Eigen::Matrix4d Similarity3::Matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = scale * rotation.toRotationMatrix();
  m.topRightCorner<3, 1>() = translation;
  return m;
}

Similarity3 Similarity3::FromMatrix(const Eigen::Matrix4d& m) {
  Similarity3 t;
  const Eigen::Matrix3d sr = m.topLeftCorner<3, 3>();
  t.scale = std::cbrt(sr.determinant());
  t.rotation = Eigen::Quaterniond(sr / t.scale).normalized();
  if (t.rotation.w() < 0) t.rotation.coeffs() *= -1;  // one sign for the same rotation
  t.translation = m.topRightCorner<3, 1>();
  return t;
}

Similarity3 Similarity3::Inverse() const {
  Similarity3 inv;
  inv.scale = 1 / scale;
  inv.rotation = rotation.conjugate();
  inv.translation = -(inv.scale * (inv.rotation * translation));
  return inv;
}

Similarity3 Similarity3::Compose(const Similarity3& first) const {
  Similarity3 out;
  out.scale = scale * first.scale;
  out.rotation = (rotation * first.rotation).normalized();
  out.translation = scale * (rotation * first.translation) + translation;
  return out;
}

Similarity3 FitSimilarityLeastSquares(const std::vector<Eigen::Vector3d>& source,
                                      const std::vector<Eigen::Vector3d>& target) {
  CINEPATH_CHECK(source.size() == target.size() && source.size() >= 3);
  std::vector<int> all(source.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  return FitSubset(source, target, all);
}

PointSpread MeasureSpread(const std::vector<Eigen::Vector3d>& points) {
  PointSpread spread;
  if (points.size() < 2) return spread;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points) cov += (p - mean) * (p - mean).transpose();
  cov /= static_cast<double>(points.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d ev = eig.eigenvalues().cwiseMax(0.0);  // ascending
  spread.along_m = std::sqrt(ev[2]);
  spread.across_m = std::sqrt(ev[0] + ev[1]);
  return spread;
}

namespace {

// Throws when `pts` are (near-)collinear: the rotation about their line would be undetermined.
void CheckSpread(const std::vector<Eigen::Vector3d>& pts, const char* which, const RobustFitOptions& options,
                 const std::string& what) {
  const PointSpread s = MeasureSpread(pts);
  const double needed = std::max(options.min_spread_ratio * s.along_m, options.min_spread_m);
  if (s.across_m < needed) {
    throw InfeasibleError("the " + what + " are (near-)collinear in " + which + ": they lie within " +
                          FormatFixed(s.across_m, 2) + " m (RMS) of a line along which they spread " +
                          FormatFixed(s.along_m, 2) + " m; the rotation about that line is undetermined (need " +
                          FormatFixed(needed, 2) + " m across)");
  }
}

// The pairs that `t` maps within the inlier threshold: their count, their flags and their summed squared residual.
int CountInliers(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                 double threshold2, const Similarity3& t, std::vector<bool>* inliers, double* sum2) {
  const int n = static_cast<int>(source.size());
  int count = 0;
  *sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double r2 = (t(source[i]) - target[i]).squaredNorm();
    const bool in = r2 <= threshold2;
    if (inliers) (*inliers)[i] = in;
    if (in) {
      ++count;
      *sum2 += r2;
    }
  }
  return count;
}

// The best similarity fitted to a triple: most inliers, then least summed squared residual.
struct RansacBest {
  Similarity3 transform;
  int count = -1;
  double sum2 = std::numeric_limits<double>::infinity();
  int trials = 0;
};

// RANSAC over triples: every triple up to 20 pairs, else `options.ransac_iterations` random ones.
RansacBest RansacOverTriples(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                             const RobustFitOptions& options, double threshold2) {
  const int n = static_cast<int>(source.size());
  double target_scale = MeasureSpread(target).along_m;
  double source_scale = MeasureSpread(source).along_m;
  const double min_area_target = 1e-6 * target_scale * target_scale;
  const double min_area_source = 1e-6 * source_scale * source_scale;
  RansacBest best;
  auto try_triple = [&](int a, int b, int c) {
    if (TriangleArea(target[a], target[b], target[c]) <= min_area_target ||
        TriangleArea(source[a], source[b], source[c]) <= min_area_source) {
      return;
    }
    ++best.trials;
    const Similarity3 t = FitSubset(source, target, {a, b, c});
    if (!IsUsable(t)) return;
    double sum2;
    const int count = CountInliers(source, target, threshold2, t, nullptr, &sum2);
    if (count > best.count || (count == best.count && sum2 < best.sum2)) {
      best.transform = t;
      best.count = count;
      best.sum2 = sum2;
    }
  };
  constexpr int kExhaustiveMax = 20;
  if (n <= kExhaustiveMax) {
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        for (int c = b + 1; c < n; ++c) try_triple(a, b, c);
  } else {
    std::mt19937_64 rng(options.seed);
    for (int it = 0; it < options.ransac_iterations; ++it) {
      const int a = static_cast<int>(rng() % n);
      int b = static_cast<int>(rng() % (n - 1));
      if (b >= a) ++b;
      int c = static_cast<int>(rng() % (n - 2));
      for (int lo : {std::min(a, b), std::max(a, b)}) {
        if (c >= lo) ++c;
      }
      try_triple(a, b, c);
    }
  }
  return best;
}

// Least squares on the inliers of `best` until the inlier set is stable (at most 10 rounds).
Similarity3 RefineOnInliers(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                            double threshold2, const Similarity3& best) {
  const int n = static_cast<int>(source.size());
  std::vector<bool> inliers(n);
  double sum2;
  CountInliers(source, target, threshold2, best, &inliers, &sum2);
  Similarity3 current = best;
  for (int round = 0; round < 10; ++round) {
    std::vector<int> idx;
    for (int i = 0; i < n; ++i)
      if (inliers[i]) idx.push_back(i);
    if (idx.size() < 3) break;
    const Similarity3 refined = FitSubset(source, target, idx);
    if (!IsUsable(refined)) break;
    std::vector<bool> next(n);
    const int count = CountInliers(source, target, threshold2, refined, &next, &sum2);
    if (count < 3) break;
    current = refined;
    if (next == inliers) break;
    inliers = next;
  }
  return current;
}

// Fills the fit's residuals, inlier flags and RMSEs for `fit.target_from_source`; returns the inliers' targets.
std::vector<Eigen::Vector3d> MeasureResiduals(const std::vector<Eigen::Vector3d>& source,
                                              const std::vector<Eigen::Vector3d>& target,
                                              const RobustFitOptions& options, RobustFit& fit) {
  const int n = static_cast<int>(source.size());
  const Similarity3& current = fit.target_from_source;
  fit.inliers.assign(n, false);
  fit.residuals_m.resize(n);
  double sum_in = 0, sum_all = 0;
  std::vector<Eigen::Vector3d> inlier_targets;
  for (int i = 0; i < n; ++i) {
    const double r = (current(source[i]) - target[i]).norm();
    fit.residuals_m[i] = r;
    fit.inliers[i] = r <= options.inlier_threshold_m;
    sum_all += r * r;
    if (fit.inliers[i]) {
      ++fit.num_inliers;
      sum_in += r * r;
      inlier_targets.push_back(target[i]);
    }
  }
  fit.rmse_all_m = std::sqrt(sum_all / n);
  fit.rmse_m = fit.num_inliers > 0 ? std::sqrt(sum_in / fit.num_inliers) : 0;
  return inlier_targets;
}

}  // namespace

RobustFit FitSimilarityRobust(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                              const RobustFitOptions& options, const std::string& what) {
  CINEPATH_CHECK(source.size() == target.size());
  const int n = static_cast<int>(source.size());
  if (n < 3) {
    throw InfeasibleError("georeferencing needs at least 3 usable " + what + ", found " + std::to_string(n));
  }
  CheckSpread(target, "ENU", options, what);

  const double threshold2 = options.inlier_threshold_m * options.inlier_threshold_m;
  const RansacBest best = RansacOverTriples(source, target, options, threshold2);
  if (best.count < 3) {
    throw InfeasibleError("georeferencing failed: no similarity fits 3 or more of the " + std::to_string(n) + " " +
                          what + " within " + FormatFixed(options.inlier_threshold_m, 2) +
                          " m (inlier threshold); the references may not belong to this model");
  }

  RobustFit fit;
  fit.ransac_trials = best.trials;
  fit.target_from_source = RefineOnInliers(source, target, threshold2, best.transform);
  const std::vector<Eigen::Vector3d> inlier_targets = MeasureResiduals(source, target, options, fit);
  if (fit.num_inliers < 3) {
    throw InfeasibleError("georeferencing failed: only " + std::to_string(fit.num_inliers) + " of " +
                          std::to_string(n) + " " + what + " fit within " + FormatFixed(options.inlier_threshold_m, 2) +
                          " m");
  }
  CheckSpread(inlier_targets, "ENU (inliers)", options, what);
  if (fit.rmse_m > options.max_rmse_m) {
    throw InfeasibleError("georeferencing RMSE " + FormatFixed(fit.rmse_m, 3) + " m over " +
                          std::to_string(fit.num_inliers) + " inlier " + what + " exceeds the maximum " +
                          FormatFixed(options.max_rmse_m, 3) + " m (`max_rmse_m`)");
  }
  return fit;
}

}  // namespace cinepath::photogrammetry
