#include "photogrammetry/texture/exposure_gain.h"

#include <random>

#include <gtest/gtest.h>

namespace cinepath::photogrammetry {
namespace {

TEST(ExposureGain, RecoversKnownGainsUpToTheirGeometricMean) {
  // Three photos that saw the same faces with exposures 1, 0.5 and 1.6 (per channel different for the
  // third): the gains that level them are 1 / exposure, divided by their geometric mean.
  const std::vector<Eigen::Vector3f> exposure = {{1, 1, 1}, {0.5f, 0.5f, 0.5f}, {1.6f, 1.4f, 1.2f}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> albedo(0.05f, 0.6f);
  std::vector<OverlapSample> samples;
  for (int f = 0; f < 300; ++f) {
    const Eigen::Vector3f c(albedo(rng), albedo(rng), albedo(rng));
    OverlapSample s;
    for (int v = 0; v < 3; ++v) {
      if ((f + v) % 4 == 0) continue;  // not every photo sees every face
      s.colors.emplace_back(v, c.cwiseProduct(exposure[size_t(v)]));
    }
    samples.push_back(s);
  }
  ExposureGainOptions options;
  options.max_ratio = 4;
  const ExposureGains g = FitExposureGains(3, samples, options);
  EXPECT_GT(g.pairs_used, 300);
  for (int k = 0; k < 3; ++k) {
    double log_mean = 0;
    for (int v = 0; v < 3; ++v) log_mean += std::log(1.0 / exposure[size_t(v)][k]) / 3;
    for (int v = 0; v < 3; ++v) {
      // The weak prior toward 1 biases the gains by a little (about 0.3 % here).
      EXPECT_NEAR(g.gain[size_t(v)][k], (1.0 / exposure[size_t(v)][k]) / std::exp(log_mean), 1e-2) << v << k;
    }
  }
  EXPECT_LT(g.rms_after, 0.02 * g.rms_before);
  EXPECT_GT(g.rms_before, 0.05);
}

TEST(ExposureGain, WithoutOverlapsEveryGainIsOne) {
  const ExposureGains g = FitExposureGains(2, {});
  ASSERT_EQ(g.gain.size(), 2u);
  EXPECT_EQ(g.gain[0], Eigen::Vector3f::Ones());
  EXPECT_EQ(g.pairs_used, 0);
}

TEST(ExposureGain, PairsThatDisagreeTooMuchAreLeftOut) {
  OverlapSample s;
  s.colors = {{0, Eigen::Vector3f(0.5f, 0.5f, 0.5f)}, {1, Eigen::Vector3f(0.05f, 0.5f, 0.5f)}};  // red 10x off
  const ExposureGains g = FitExposureGains(2, {s});
  EXPECT_EQ(g.pairs_rejected, 1);
  EXPECT_EQ(g.pairs_used, 0);
}

}  // namespace
}  // namespace cinepath::photogrammetry
