#include "shots/lens_track.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/optics.h"

namespace cinepath::shots {

double InterpolateFocalLengthMm(double f0_mm, double f1_mm, double w) {
  if (w <= 0) return f0_mm;
  if (w >= 1) return f1_mm;
  return std::exp((1.0 - w) * std::log(f0_mm) + w * std::log(f1_mm));
}

double InterpolateFocusDistanceM(double s0_m, double s1_m, double w) {
  if (w <= 0) return s0_m;
  if (w >= 1) return s1_m;
  const double d0 = std::isinf(s0_m) ? 0.0 : 1.0 / s0_m;
  const double d1 = std::isinf(s1_m) ? 0.0 : 1.0 / s1_m;
  const double d = (1.0 - w) * d0 + w * d1;
  return d <= 0 ? std::numeric_limits<double>::infinity() : 1.0 / d;
}

double InterpolateFNumber(double n0, double n1, double w) {
  if (w <= 0) return n0;
  if (w >= 1) return n1;
  return std::exp2((1.0 - w) * std::log2(n0) + w * std::log2(n1));
}

double InterpolateShutterS(double t0_s, double t1_s, double w) { return InterpolateFocalLengthMm(t0_s, t1_s, w); }

double FramingFocalLengthMm(double image_height_mm, double subject_height_m, double distance_m,
                            double height_fraction) {
  if (!(subject_height_m > 0) || !(distance_m > 0) || !(height_fraction > 0) || !(image_height_mm > 0)) {
    throw InputError("framing: subject height, distance, frame fraction and image height must be > 0");
  }
  const double vfov = 2.0 * std::atan(subject_height_m / (2.0 * distance_m * height_fraction));
  return FocalLengthForFieldOfViewMm(image_height_mm, vfov);
}

double ImageHeightFraction(double image_height_mm, double focal_length_mm, double subject_height_m, double distance_m) {
  const double vfov = FieldOfViewRad(image_height_mm, focal_length_mm);
  return subject_height_m / (2.0 * distance_m * std::tan(vfov / 2.0));
}

double InterpolateLensKeys(const std::vector<ScalarKey>& keys, double time_s, LensQuantity quantity) {
  CINEPATH_CHECK(!keys.empty());
  if (time_s <= keys.front().time_s) return keys.front().value;
  if (time_s >= keys.back().time_s) return keys.back().value;
  const auto it =
      std::upper_bound(keys.begin(), keys.end(), time_s, [](double t, const ScalarKey& k) { return t < k.time_s; });
  const ScalarKey& b = *it;
  const ScalarKey& a = *(it - 1);
  const double w = (time_s - a.time_s) / (b.time_s - a.time_s);
  switch (quantity) {
    case LensQuantity::kFocalLength: return InterpolateFocalLengthMm(a.value, b.value, w);
    case LensQuantity::kFocusDistance: return InterpolateFocusDistanceM(a.value, b.value, w);
    case LensQuantity::kFNumber: return InterpolateFNumber(a.value, b.value, w);
    case LensQuantity::kShutter: return InterpolateShutterS(a.value, b.value, w);
  }
  return a.value;
}

}  // namespace cinepath::shots
