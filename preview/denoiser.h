// A denoiser for the noise of few lens rays (`render --denoise`; docs/render.md, "Denoising"): a
// weighted mean of each blurred pixel's neighbours, guided by the blur-circle diameter at each pixel's depth
// (a neighbour blurred otherwise is at another depth: another object, kept apart). A blurred pixel's true
// colour changes only over a distance comparable with its blur, so the kernel's width is a fraction of the
// blur, and narrower the more rays the pixel had (as 1 / sqrt(rays): the kernel then averages about the same
// number of rays whatever the count, and its bias fades as the rays converge). Sharp pixels are never touched.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace cinepath::preview {

struct DenoiseGuide {
  int width = 0;
  int height = 0;
  std::vector<float> blur_px;  // blur-circle diameter at the depth the pixel centre sees (the pinhole pass)
  std::vector<uint8_t> noisy;  // 1: the pixel's colour is a mean of lens rays (the pixels the filter may change)
  std::vector<uint16_t> rays;  // how many
};

// The kernel: a Gaussian of standard deviation kDenoiseBlurFraction * blur / 2 / sqrt(rays) (blur as a
// diameter, px), cut at two standard deviations and never wider than kDenoiseMaxRadiusPx; times a Gaussian
// in the neighbour's blur difference, of standard deviation kDenoiseBlurTolerance times the pixel's blur
// plus half a pixel. bench/RESULTS.md has the figures these were chosen by.
inline constexpr float kDenoiseBlurFraction = 0.4f;
inline constexpr float kDenoiseBlurTolerance = 0.15f;
inline constexpr int kDenoiseMaxRadiusPx = 16;

// rgb_linear denoised: every noisy pixel with at least half a pixel of blur replaced by its weighted
// neighbourhood mean; the others as they were. Deterministic at any thread count.
std::vector<Eigen::Vector3f> DenoiseBlurred(const std::vector<Eigen::Vector3f>& rgb_linear, const DenoiseGuide& guide);

}  // namespace cinepath::preview
