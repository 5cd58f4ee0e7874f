#include "preview/denoiser.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"

namespace cinepath::preview {
namespace {

constexpr float kSharpPx = 0.5f;  // as the renderer's: under half a pixel of blur a pixel took one pinhole ray
constexpr float kNegligibleWeightExponent = 9.0f;  // e^-9 = 1.2e-4

// e^-x for x in [0, kNegligibleWeightExponent], the nearest of 512 entries a unit (relative error under
// e^(1/1024) - 1 = 0.1 %): the filter takes one per tap, and the library's exp was a third of its time, a
// table with linear interpolation between entries a quarter.
class NegativeExp {
 public:
  NegativeExp() {
    for (int i = 0; i <= kSteps; ++i) table_[i] = std::exp(-float(i) / kPerUnit);
  }
  float operator()(float x) const { return table_[int(x * kPerUnit + 0.5f)]; }

 private:
  static constexpr int kPerUnit = 512;
  static constexpr int kSteps = int(kNegligibleWeightExponent) * kPerUnit;
  float table_[kSteps + 1];
};

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "the filter walks the colours as packed floats");

void ForEachRow(int h, const std::function<void(int)>& row) {
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) row(y);
  });
}

// One pass of the filter along x (axis 0) or y (axis 1): the kernel is separable in its space term, and
// two passes of 2r + 1 taps cost what one of (2r + 1)^2 would cost 2r + 1 times over (the blur term makes
// the pair an approximation of the two-dimensional kernel, as for separable bilateral filters).
// `key`: each pixel's blur where it had lens rays, -inf elsewhere (such a neighbour's weight is then 0).
std::vector<Eigen::Vector3f> FilterAlong(int axis, const std::vector<Eigen::Vector3f>& in, const DenoiseGuide& guide,
                                         const std::vector<float>& key, float blur_fraction) {
  static const NegativeExp negative_exp;
  const int w = guide.width, h = guide.height;
  const ptrdiff_t stride = axis == 0 ? 1 : w;
  std::vector<Eigen::Vector3f> out = in;
  ForEachRow(h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * w + x;
      const float blur_p = std::min(key[p], 1e4f);
      if (!(blur_p >= kSharpPx)) continue;  // sharp, or no lens rays
      const float rays = std::max<float>(1, guide.rays[p]);
      // Narrower than a third of a pixel, the kernel would give the neighbours under e^-4.5 of the weight.
      const float sigma = std::min(blur_fraction * blur_p / 2 / std::sqrt(rays), kDenoiseMaxRadiusPx / 2.0f);
      if (sigma < 1.0f / 3) continue;
      const int radius = std::min(kDenoiseMaxRadiusPx, int(std::ceil(2 * sigma)));
      const int at = axis == 0 ? x : y, size = axis == 0 ? w : h;
      const int d_first = std::max(-radius, -at), d_last = std::min(radius, size - 1 - at);
      const float inv_two_sigma2 = 1 / (2 * sigma * sigma);
      const float blur_scale = kDenoiseBlurTolerance * blur_p + 0.5f;
      const float inv_two_blur_scale2 = 1 / (2 * blur_scale * blur_scale);
      const float* key_q = key.data() + ptrdiff_t(p) + d_first * stride;
      const float* in_q = in[size_t(ptrdiff_t(p) + d_first * stride)].data();
      const ptrdiff_t in_stride = 3 * stride;  // Vector3f is three packed floats
      float r = 0, g = 0, b = 0, weight = 0;
      for (int d = d_first; d <= d_last; ++d, key_q += stride, in_q += in_stride) {
        const float db = *key_q - blur_p;
        const float exponent = float(d * d) * inv_two_sigma2 + db * db * inv_two_blur_scale2;
        if (!(exponent <= kNegligibleWeightExponent)) continue;
        const float wq = negative_exp(exponent);
        r += wq * in_q[0];
        g += wq * in_q[1];
        b += wq * in_q[2];
        weight += wq;
      }
      if (weight > 0) out[p] = Eigen::Vector3f(r, g, b) / weight;
    }
  });
  return out;
}

}  // namespace

std::vector<Eigen::Vector3f> DenoiseBlurred(const std::vector<Eigen::Vector3f>& rgb_linear, const DenoiseGuide& guide) {
  const size_t n = size_t(guide.width) * size_t(guide.height);
  CINEPATH_CHECK(rgb_linear.size() == n && guide.blur_px.size() == n && guide.noisy.size() == n &&
                 guide.rays.size() == n);
  std::vector<float> key(n);
  for (size_t p = 0; p < n; ++p) key[p] = guide.noisy[p] ? guide.blur_px[p] : -std::numeric_limits<float>::infinity();
  return FilterAlong(1, FilterAlong(0, rgb_linear, guide, key, kDenoiseBlurFraction), guide, key, kDenoiseBlurFraction);
}

}  // namespace cinepath::preview
