// The denoiser on images whose answer is known: noise over a uniform blurred surface goes, its mean stays;
// sharp pixels, pixels without lens rays and a neighbour at another depth are left alone; the kernel
// narrows as the rays grow; the same pixels on one thread and on all.
#include "preview/denoiser.h"

#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

namespace cinepath::preview {
namespace {

constexpr int kW = 96;
constexpr int kH = 48;

DenoiseGuide UniformGuide(float blur_px, uint16_t rays) {
  DenoiseGuide guide;
  guide.width = kW;
  guide.height = kH;
  guide.blur_px.assign(size_t(kW) * kH, blur_px);
  guide.noisy.assign(size_t(kW) * kH, 1);
  guide.rays.assign(size_t(kW) * kH, rays);
  return guide;
}

// 0.5 grey plus uniform noise of +-amplitude per channel (a fixed linear congruential sequence).
std::vector<Eigen::Vector3f> NoisyGrey(float amplitude) {
  std::vector<Eigen::Vector3f> rgb(size_t(kW) * kH);
  uint32_t state = 12345;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) * 2 - 1;
  };
  for (auto& c : rgb) {
    const float x = next(), y = next(), z = next();
    c = Eigen::Vector3f(0.5f + amplitude * x, 0.5f + amplitude * y, 0.5f + amplitude * z);
  }
  return rgb;
}

// Root-mean-square distance from grey 0.5 and the mean, over the pixels away from the border.
std::pair<double, double> ErrorAndMean(const std::vector<Eigen::Vector3f>& rgb) {
  double sum2 = 0, sum = 0;
  int count = 0;
  for (int y = 8; y < kH - 8; ++y) {
    for (int x = 8; x < kW - 8; ++x) {
      const Eigen::Vector3f& c = rgb[size_t(y) * kW + x];
      sum2 += (c - Eigen::Vector3f::Constant(0.5f)).squaredNorm() / 3;
      sum += c.sum() / 3;
      ++count;
    }
  }
  return {std::sqrt(sum2 / count), sum / count};
}

TEST(Denoiser, NoiseOverAUniformBlurredSurfaceFallsAndItsMeanStays) {
  const std::vector<Eigen::Vector3f> noisy = NoisyGrey(0.3f);
  const auto [before, mean_before] = ErrorAndMean(noisy);
  const auto [after, mean_after] = ErrorAndMean(DenoiseBlurred(noisy, UniformGuide(20, 1)));
  // sigma = 0.4 * 20 / 2 = 4 px: a Gaussian over ~200 pixels, so the noise falls ~14x.
  EXPECT_LT(after, before / 8) << before << " -> " << after;
  EXPECT_NEAR(mean_after, mean_before, 0.005);
}

TEST(Denoiser, SharpPixelsAndPixelsWithoutLensRaysAreLeftAlone) {
  const std::vector<Eigen::Vector3f> noisy = NoisyGrey(0.3f);
  DenoiseGuide guide = UniformGuide(20, 1);
  for (int x = 0; x < kW; ++x) {
    guide.blur_px[size_t(10) * kW + x] = 0.3f;  // row 10: in focus
    guide.noisy[size_t(20) * kW + x] = 0;       // row 20: its pinhole ray, no lens rays
  }
  const std::vector<Eigen::Vector3f> out = DenoiseBlurred(noisy, guide);
  for (int x = 0; x < kW; ++x) {
    for (int y : {10, 20}) {
      const size_t i = size_t(y) * kW + x;
      EXPECT_EQ(out[i], noisy[i]) << "row " << y << ", column " << x;
    }
  }
  EXPECT_NE(out[size_t(30) * kW + 40], noisy[size_t(30) * kW + 40]);
}

TEST(Denoiser, ANeighbourBlurredOtherwiseIsAnotherDepthAndStaysOut) {
  // Left half: a dark surface blurred 20 px; right half: a bright one blurred 3 px (another depth). The
  // left's pixels beside the boundary take in none of the right's brightness, and the other way round.
  std::vector<Eigen::Vector3f> rgb(size_t(kW) * kH);
  DenoiseGuide guide = UniformGuide(20, 1);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) {
      const size_t i = size_t(y) * kW + x;
      const bool right = x >= kW / 2;
      rgb[i] = Eigen::Vector3f::Constant(right ? 1.0f : 0.0f);
      guide.blur_px[i] = right ? 3.0f : 20.0f;
    }
  }
  const std::vector<Eigen::Vector3f> out = DenoiseBlurred(rgb, guide);
  for (int y = 0; y < kH; ++y) {
    EXPECT_LT(out[size_t(y) * kW + kW / 2 - 1].x(), 1e-3f) << "row " << y;
    EXPECT_GT(out[size_t(y) * kW + kW / 2].x(), 1 - 1e-3f) << "row " << y;
  }
}

TEST(Denoiser, TheKernelNarrowsAsTheRaysGrow) {
  // A noiseless step within one surface blurred 20 px: the filter can only widen it, less with more rays.
  std::vector<Eigen::Vector3f> step(size_t(kW) * kH);
  for (int y = 0; y < kH; ++y) {
    for (int x = 0; x < kW; ++x) step[size_t(y) * kW + x] = Eigen::Vector3f::Constant(x < kW / 2 ? 0.0f : 1.0f);
  }
  auto widened = [&](uint16_t rays) {
    const std::vector<Eigen::Vector3f> out = DenoiseBlurred(step, UniformGuide(20, rays));
    double change = 0;
    for (size_t i = 0; i < out.size(); ++i) change += (out[i] - step[i]).cwiseAbs().sum() / 3;
    return change / kH;  // summed along a row: about the step's added width in pixels
  };
  const double one = widened(1), four = widened(4), many = widened(256);
  EXPECT_GT(one, 1.0);
  EXPECT_NEAR(four, one / 2, one * 0.1);  // sigma as 1 / sqrt(rays)
  EXPECT_LT(many, 0.15);
}

TEST(Denoiser, TheSamePixelsOnOneThreadAndOnAll) {
  const std::vector<Eigen::Vector3f> noisy = NoisyGrey(0.3f);
  DenoiseGuide guide = UniformGuide(12, 2);
  for (size_t i = 0; i < guide.blur_px.size(); ++i) guide.blur_px[i] = 4 + float(i % 37);
  const std::vector<Eigen::Vector3f> all = DenoiseBlurred(noisy, guide);
  std::vector<Eigen::Vector3f> one;
  tbb::task_arena arena(1);
  arena.execute([&] { one = DenoiseBlurred(noisy, guide); });
  ASSERT_EQ(one.size(), all.size());
  for (size_t i = 0; i < all.size(); ++i) ASSERT_EQ(one[i], all[i]) << i;
}

}  // namespace
}  // namespace cinepath::preview
