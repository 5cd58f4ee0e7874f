// Thin-lens optics: the one module that computes blur, depth of field and field of view for every
// stage (the planner, the optimizer, the renderer and the exporters). Formulas and conventions:
// docs/optics.md.
//
// Symbols: f focal length, N f-number, s focus distance (object side, from the lens), d subject
// distance along the optical axis, c blur-circle diameter on the sensor, c0 acceptable blur.
// Distances are metres, focal lengths and sensor sizes millimetres, as the names say. A focus
// distance of +infinity means focused at infinity. Domain errors (d <= f, s <= f, N <= 0,
// non-finite input) throw InputError naming the quantity.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cinepath {

struct Filmback {
  std::string name;   // preset key, e.g. "super35"
  std::string label;  // human name, e.g. "Super 35"
  double width_mm = 0;
  double height_mm = 0;
  double DiagonalMm() const;
};

// Presets: super35, digital-film-16x9, full-frame, aps-c, micro-four-thirds, one-inch,
// and the small drone sensors (one-over-2.3-inch). See docs/optics.md for sources.
const std::vector<Filmback>& FilmbackPresets();
std::optional<Filmback> FindFilmback(std::string_view name);

// The conventional acceptable blur for a filmback: 0.03 mm on full frame (43.27 mm diagonal),
// scaled by the diagonal: c0 = 0.03 mm * diagonal / 43.27 mm.
double DefaultCocMm(double sensor_width_mm, double sensor_height_mm);

// Validation, shared with callers that want to name their own option in the message.
void ValidateFocalLengthMm(double focal_length_mm, const std::string& what = "focal length");
void ValidateFNumber(double f_number, const std::string& what = "f-number");
// s > f (or +infinity).
void ValidateFocusDistanceM(double focus_distance_m, double focal_length_mm,
                            const std::string& what = "focus distance");

// Blur-circle diameter on the sensor, mm, for a point at distance d when focused at s (stable form):
//   c = (f^2 / N) * |1/s - 1/d| / (1 - f/s)
// s = +inf gives c = f^2 / (N d); d = +inf gives c = (f^2/N) (1/s) / (1 - f/s).
double BlurCircleMm(double focal_length_mm, double f_number, double focus_distance_m, double subject_distance_m);

// The same thin lens in dioptres, templated so that automatic differentiation (optimize) runs through it;
// metres and dioptres (1/m, 0 at infinity), no validation. BlurCircleMm is this with checked inputs.
//   blur-circle diameter c = (f^2 / N) |D - B| / (1 - f D)        focus at 1/D, point at 1/B
//   depth of field: 1/near = D + K (1 - f D), 1/far = D - K (1 - f D), K = N c0 / f^2 (the limits of
//   DepthOfFieldLimits, symmetric in dioptres about the focus); this returns K (1 - f D).
// One lens focused at 1/D, for the blur circles of many points: its terms f^2 / N and 1 - f D worked out
// once, the rest per point in the formula's own order (BlurCircleDiameterM is this, the same bits).
template <typename T>
struct FocusedLens {
  FocusedLens(const T& focal_m, const T& f_number, const T& focus_dioptre)
      : f2_over_n(focal_m * focal_m / f_number),
        focus_dioptre(focus_dioptre),
        denominator(T(1) - focal_m * focus_dioptre) {}
  T BlurCircleDiameterM(const T& point_dioptre) const {
    using std::abs;
    return f2_over_n * abs(focus_dioptre - point_dioptre) / denominator;
  }
  T f2_over_n;
  T focus_dioptre;
  T denominator;
};
template <typename T>
T BlurCircleDiameterM(const T& focal_m, const T& f_number, const T& focus_dioptre, const T& point_dioptre) {
  return FocusedLens<T>(focal_m, f_number, focus_dioptre).BlurCircleDiameterM(point_dioptre);
}
template <typename T>
T DepthOfFieldHalfWidthDioptres(const T& focal_m, const T& f_number, const T& focus_dioptre, double coc_m) {
  return f_number * coc_m / (focal_m * focal_m) * (T(1) - focal_m * focus_dioptre);
}

// mm on the sensor to pixels: c_px = c * width_px / sensor_width_mm.
double MmToPixels(double sensor_mm, double sensor_width_mm, int width_px);

// Hyperfocal distance H = f^2 / (N c0) + f, metres.
double HyperfocalDistanceM(double focal_length_mm, double f_number, double coc_mm);

struct DepthOfField {
  double hyperfocal_m = 0;
  double near_m = 0;
  double far_m = 0;  // +infinity when focus >= hyperfocal
};

// near = s (H - f) / (H + s - 2f); far = s (H - f) / (H - s), infinite when s >= H.
// s = +inf gives near = H - f, far = +inf.
DepthOfField DepthOfFieldLimits(double focal_length_mm, double f_number, double focus_distance_m, double coc_mm);

// Aperture difference in stops: 2 log2(n1 / n0) (a stop is a factor sqrt(2) of f-number).
inline double StopsBetween(double n0, double n1) { return 2.0 * std::log2(n1 / n0); }

// Angle of view across a sensor extent: 2 atan(extent / (2 f)), radians (focus at infinity, no
// focus breathing).
double FieldOfViewRad(double sensor_extent_mm, double focal_length_mm);
// Inverse: the focal length giving that angle of view across the extent.
double FocalLengthForFieldOfViewMm(double sensor_extent_mm, double field_of_view_rad);

// Sensor fit: the one rule every stage uses (plan's framing and subjects_in_frame, lens, render,
// view). The image spans the full sensor width; its height covers width_mm * height_px / width_px of
// the sensor, centred. This is Blender Cycles' HORIZONTAL sensor fit, and Unreal's CineCamera also
// takes the horizontal angle of view from the filmback width (docs/optics.md, "Sensor fit"). A 4:3
// Super 35 filmback (24.89 x 18.67 mm) with a 3840 x 2160 image uses 24.89 x 14.00 mm.
struct ImageExtentMm {
  double width_mm = 0;
  double height_mm = 0;
};
// InputError when the sensor width or a pixel count is not positive.
ImageExtentMm ImageExtentOnSensorMm(double sensor_width_mm, int width_px, int height_px);

// Lateral magnification of an object at distance d: m = f / (d - f) (image size / object size).
double MagnificationAt(double focal_length_mm, double subject_distance_m);

}  // namespace cinepath
