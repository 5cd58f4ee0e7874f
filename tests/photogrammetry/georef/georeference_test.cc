#include "photogrammetry/georef/georeference.h"

#include <gtest/gtest.h>

#include <random>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

Similarity3 Truth() {
  Similarity3 t;
  t.scale = 7.5;
  t.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.2, -0.4, 0.9).normalized()));
  t.translation = {-12, 40, 150};
  return t;
}

// A drone survey: 4 flight lines of 8 photos over 100 m x 45 m, at 40 m +- 0.5 m.
void MakePairs(int n_lines, int per_line, double noise_m, uint64_t seed, std::vector<Eigen::Vector3d>* colmap,
               std::vector<Eigen::Vector3d>* enu) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, noise_m);
  const Similarity3 colmap_from_enu = Truth().Inverse();
  for (int l = 0; l < n_lines; ++l) {
    for (int k = 0; k < per_line; ++k) {
      const Eigen::Vector3d p(k * 14.0 - 50, l * 15.0 - 22, 40 + 0.5 * std::sin(l * 7 + k));
      colmap->push_back(colmap_from_enu(p));
      enu->push_back(p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    }
  }
}

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return Eigen::AngleAxisd(a.conjugate() * b).angle() * 180 / M_PI;
}

TEST(Similarity3, ComposeInverseAndMatrixAgree) {
  const Similarity3 t = Truth();
  const Eigen::Vector3d x(1, 2, 3);
  EXPECT_LT((t.Inverse()(t(x)) - x).norm(), 1e-12);
  EXPECT_LT((t.Compose(t.Inverse())(x) - x).norm(), 1e-12);
  const Similarity3 m = Similarity3::FromMatrix(t.Matrix());
  EXPECT_NEAR(m.scale, t.scale, 1e-12);
  EXPECT_LT((m(x) - t(x)).norm(), 1e-10);
}

TEST(FitSimilarityRobust, ExactDataIsRecoveredExactly) {
  std::vector<Eigen::Vector3d> src, dst;
  MakePairs(3, 6, 0.0, 1, &src, &dst);
  const RobustFit fit = FitSimilarityRobust(src, dst, RobustFitOptions());
  EXPECT_NEAR(fit.target_from_source.scale, 7.5, 1e-9);
  EXPECT_LT(AngleDeg(fit.target_from_source.rotation, Truth().rotation), 1e-7);
  EXPECT_LT((fit.target_from_source.translation - Truth().translation).norm(), 1e-7);
  EXPECT_EQ(fit.num_inliers, 18);
  EXPECT_LT(fit.rmse_m, 1e-8);
}

// Tolerances: with 1 m GPS noise on 32 references spread over ~100 m, the scale is within 1 %, the
// rotation within 1 degree, and the fitted positions within 1.2 m of the truth.
TEST(FitSimilarityRobust, NoisyReferencesWithinTolerances) {
  std::vector<Eigen::Vector3d> src, dst;
  MakePairs(4, 8, 1.0, 2, &src, &dst);
  const RobustFit fit = FitSimilarityRobust(src, dst, RobustFitOptions());
  EXPECT_NEAR(fit.target_from_source.scale / 7.5, 1.0, 0.01);
  EXPECT_LT(AngleDeg(fit.target_from_source.rotation, Truth().rotation), 1.0);
  for (const auto& s : src) EXPECT_LT((fit.target_from_source(s) - Truth()(s)).norm(), 1.2);
  EXPECT_NEAR(fit.rmse_m, std::sqrt(3.0), 0.5);  // 1 m per axis
  EXPECT_GE(fit.num_inliers, 30);
}

// 30 % of the references wrong by 50 m (e.g. a GPS glitch); with 1 m noise on the rest.
TEST(FitSimilarityRobust, ThirtyPercentOfReferencesFiftyMetresOff) {
  for (int lines : {3, 5}) {  // 18 pairs: exhaustive triples; 40 pairs: seeded random sampling
    std::vector<Eigen::Vector3d> src, dst;
    MakePairs(lines, lines == 3 ? 6 : 8, 1.0, 3, &src, &dst);
    std::mt19937_64 rng(5);
    const int n = static_cast<int>(src.size());
    std::vector<bool> bad(n, false);
    int n_bad = 0;
    while (n_bad < (3 * n) / 10) {
      const int i = static_cast<int>(rng() % n);
      if (bad[i]) continue;
      bad[i] = true;
      ++n_bad;
      const Eigen::Vector3d dir = Eigen::Vector3d(std::sin(i), std::cos(i), 0.3 * std::sin(2 * i)).normalized();
      dst[i] += 50 * dir;
    }
    const RobustFit fit = FitSimilarityRobust(src, dst, RobustFitOptions());
    EXPECT_NEAR(fit.target_from_source.scale / 7.5, 1.0, 0.015) << lines;
    EXPECT_LT(AngleDeg(fit.target_from_source.rotation, Truth().rotation), 1.5) << lines;
    for (const auto& s : src) EXPECT_LT((fit.target_from_source(s) - Truth()(s)).norm(), 1.0) << lines;
    for (int i = 0; i < n; ++i) EXPECT_EQ(fit.inliers[i], !bad[i]) << lines << " " << i;
    EXPECT_EQ(fit.num_inliers, n - n_bad);
    EXPECT_GT(fit.rmse_all_m, 10.0);  // the outliers show in the all-pairs RMSE
    EXPECT_LT(fit.rmse_m, 3.0);
    // Deterministic: the same seed gives the same answer.
    const RobustFit again = FitSimilarityRobust(src, dst, RobustFitOptions());
    EXPECT_EQ(again.target_from_source.translation, fit.target_from_source.translation);
    // A plain least-squares fit is pulled far off by the outliers.
    const Similarity3 ls = FitSimilarityLeastSquares(src, dst);
    double worst = 0;
    for (const auto& s : src) worst = std::max(worst, (ls(s) - Truth()(s)).norm());
    EXPECT_GT(worst, 5.0);
  }
}

std::string InfeasibleMessage(const std::vector<Eigen::Vector3d>& src, const std::vector<Eigen::Vector3d>& dst,
                              const RobustFitOptions& options = RobustFitOptions()) {
  try {
    FitSimilarityRobust(src, dst, options);
  } catch (const InfeasibleError& e) {
    return e.what();
  }
  return "";
}

TEST(FitSimilarityRobust, RefusesTooFewCollinearOrPoorReferences) {
  std::vector<Eigen::Vector3d> src, dst;
  MakePairs(1, 2, 0.0, 1, &src, &dst);
  EXPECT_NE(InfeasibleMessage(src, dst).find("at least 3 usable references, found 2"), std::string::npos);

  src.clear();
  dst.clear();
  MakePairs(1, 8, 0.1, 1, &src, &dst);  // one straight flight line
  const std::string collinear = InfeasibleMessage(src, dst);
  EXPECT_NE(collinear.find("(near-)collinear"), std::string::npos) << collinear;

  src.clear();
  dst.clear();
  MakePairs(4, 8, 2.0, 9, &src, &dst);
  RobustFitOptions strict;
  strict.max_rmse_m = 1.0;
  const std::string rmse = InfeasibleMessage(src, dst, strict);
  EXPECT_NE(rmse.find("exceeds the maximum 1.000 m"), std::string::npos) << rmse;

  // References from another site: nothing fits.
  src.clear();
  dst.clear();
  MakePairs(4, 8, 0.0, 9, &src, &dst);
  std::mt19937_64 rng(1);
  for (auto& d : dst) d = Eigen::Vector3d(rng() % 1000, rng() % 1000, rng() % 100);
  const std::string none = InfeasibleMessage(src, dst);
  EXPECT_NE(none.find("georeferencing"), std::string::npos) << none;
  EXPECT_TRUE(none.find("failed") != std::string::npos || none.find("exceeds") != std::string::npos) << none;
}

}  // namespace
}  // namespace cinepath::photogrammetry
