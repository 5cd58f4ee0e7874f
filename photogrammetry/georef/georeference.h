// Robust similarity between a reconstruction frame and local ENU metres.
//
// Given matched pairs (source point in the COLMAP frame, target point in ENU), FitSimilarityRobust
// finds enu = s R colmap + t:
//   1. RANSAC over minimal 3-point sets: every triple when there are few pairs (<= 20: at most 1140
//      triples, exhaustive and deterministic), else `ransac_iterations` triples drawn with a
//      std::mt19937_64 seeded by `seed` (deterministic for a given seed); each triple is fitted with
//      Eigen::umeyama, pairs within `inlier_threshold_m` are inliers; the most inliers win, ties go to
//      the lower sum of squared inlier residuals.
//   2. Least squares (Eigen::umeyama) on the inliers, re-selecting inliers with the refined
//      transform until the set stops changing (at most 10 rounds).
// Refused with InfeasibleError (exit 3), saying why, when there are fewer than 3 pairs or inliers, the
// targets (or sources) are (near-)collinear, or the inlier RMSE exceeds `max_rmse_m`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cinepath::photogrammetry {

// x_b = scale * rotation * x_a + translation.
struct Similarity3 {
  double scale = 1;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // Hamilton, unit
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator()(const Eigen::Vector3d& x) const { return scale * (rotation * x) + translation; }
  Eigen::Matrix4d Matrix() const;
  static Similarity3 FromMatrix(const Eigen::Matrix4d& m);  // m = [sR t; 0 1]
  Similarity3 Inverse() const;
  // (this ∘ first)(x) = this(first(x)).
  Similarity3 Compose(const Similarity3& first) const;
};

// Least-squares similarity (Umeyama 1991, via Eigen::umeyama); needs >= 3 non-collinear pairs.
Similarity3 FitSimilarityLeastSquares(const std::vector<Eigen::Vector3d>& source,
                                      const std::vector<Eigen::Vector3d>& target);

struct RobustFitOptions {
  double inlier_threshold_m = 5.0;  // a pair is an inlier when |T(source) - target| <= this
  double max_rmse_m = 3.0;          // refuse when the inlier RMSE exceeds this
  // Refuse (near-)collinear targets: the RMS distance of the points from their best-fit line must be
  // at least max(min_spread_ratio * RMS extent along the line, min_spread_m).
  double min_spread_ratio = 0.02;
  double min_spread_m = 0.5;
  int ransac_iterations = 2000;  // used when there are more than 20 pairs
  uint64_t seed = 1;
};

struct RobustFit {
  Similarity3 target_from_source;
  std::vector<double> residuals_m;  // |T(source_i) - target_i| for every pair
  std::vector<bool> inliers;
  int num_inliers = 0;
  double rmse_m = 0;      // over the inliers
  double rmse_all_m = 0;  // over every pair
  int ransac_trials = 0;
};

// `what` names the data in refusal messages (e.g. "references").
RobustFit FitSimilarityRobust(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                              const RobustFitOptions& options, const std::string& what = "references");

// How far a point set spreads along its principal direction and away from its best-fit line (RMS).
struct PointSpread {
  double along_m = 0;   // RMS extent along the principal direction
  double across_m = 0;  // RMS distance from the best-fit line
};
PointSpread MeasureSpread(const std::vector<Eigen::Vector3d>& points);

}  // namespace cinepath::photogrammetry
