// Exposure levelling between photos: one gain per photo and colour channel, fitted by least squares on
// the overlaps, so that a face seen by two photos has the same colour in both once each is multiplied
// by its gain (the global part of Waechter et al. 2014's colour adjustment, with a gain in place of an
// additive offset, as exposure and white balance scale linear light).
//
// Per channel, with c(f, v) the mean linear colour of face f in photo v (sampled at its centroid and
// three points near its corners):
//   minimise  sum over faces f, pairs v < w of photos that both see f:  (g_v c(f, v) - g_w c(f, w))^2
//           + prior * S * sum_v (g_v - 1)^2
// where S is the mean of the data term's diagonal, so that `prior` is relative and the gains stay near
// 1 when the overlaps say little (a photo overlapping no other keeps gain 1); the gains of the photos
// that overlap are then divided by their geometric mean (the data term cannot see a common scale). Pairs whose ratio
// c(f, v) / c(f, w) lies outside [1 / max_ratio, max_ratio] (something moved, or a misregistration)
// and dark samples are left out. Solved with Eigen's LDLT: a small dense system, one unknown per photo.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace cinepath::photogrammetry {

// One face seen in several photos: (photo index, mean linear colour there), at least two entries.
struct OverlapSample {
  std::vector<std::pair<int, Eigen::Vector3f>> colors;
};

struct ExposureGainOptions {
  double prior = 0.001;
  double max_ratio = 2.0;
  double min_linear = 0.01;  // a pair with a sample darker than this in any channel is left out
};

struct ExposureGains {
  std::vector<Eigen::Vector3f> gain;  // per photo, per channel (linear)
  int64_t pairs_used = 0;
  int64_t pairs_rejected = 0;
  double rms_before = 0;  // RMS of g_v c - g_w c over the pairs used, before (all gains 1) and after
  double rms_after = 0;
};

ExposureGains FitExposureGains(int num_photos, const std::vector<OverlapSample>& samples,
                               const ExposureGainOptions& options = {});

}  // namespace cinepath::photogrammetry
