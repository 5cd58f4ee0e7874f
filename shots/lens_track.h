// Lens values the way camera operators think about them, and framing -> focal length.
//
//   focal length  interpolated in log space (equal ratios in equal times: a zoom that looks even)
//   focus         interpolated in dioptres (1 / distance; infinity = 0 dioptres), like a focus ring
//   aperture      interpolated in stops (log2 of the f-number squared)
//   shutter       interpolated in log space (stops of exposure time)
// Framing uses the vertical angle of view from core/optics.h (pinhole, focus at infinity, no
// breathing): a subject of height H at distance d fills the fraction k = H / (2 d tan(vfov / 2)) of
// the frame height, so f = FocalLengthForFieldOfViewMm(image_height, 2 atan(H / (2 d k))). The image
// height is the part of the sensor the image covers (CameraSpec::image_extent_mm, the sensor-fit rule),
// not the filmback's height.
#pragma once

#include <string>
#include <vector>

namespace cinepath::shots {

double InterpolateFocalLengthMm(double f0_mm, double f1_mm, double w);
double InterpolateFocusDistanceM(double s0_m, double s1_m, double w);  // +inf allowed
double InterpolateFNumber(double n0, double n1, double w);
double InterpolateShutterS(double t0_s, double t1_s, double w);

// Aperture difference in stops: core/optics.h StopsBetween.

// The focal length that makes a subject of `subject_height_m` at `distance_m` fill
// `height_fraction` of the frame height (0 < fraction). InputError for non-positive input.
double FramingFocalLengthMm(double image_height_mm, double subject_height_m, double distance_m, double height_fraction);
// The fraction of the frame height the subject fills with that focal length.
double ImageHeightFraction(double image_height_mm, double focal_length_mm, double subject_height_m, double distance_m);

// Keyed scalar track (times in seconds, increasing). Values hold outside the key range.
enum class LensQuantity { kFocalLength, kFocusDistance, kFNumber, kShutter };
struct ScalarKey {
  double time_s = 0;
  double value = 0;
};
double InterpolateLensKeys(const std::vector<ScalarKey>& keys, double time_s, LensQuantity quantity);

}  // namespace cinepath::shots
