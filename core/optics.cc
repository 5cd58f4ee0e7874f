#include "core/optics.h"

#include <cmath>
#include <limits>

#include "core/error.h"

namespace cinepath {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMmPerM = 1000.0;

std::string Num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void ValidateSubjectDistanceM(double d_m, double focal_length_mm) {
  if (std::isnan(d_m) || d_m == -kInf) throw InputError("subject distance must be a number");
  if (d_m * kMmPerM <= focal_length_mm) {
    throw InputError("subject distance " + Num(d_m) + " m is not beyond the focal length " + Num(focal_length_mm) +
                     " mm (no real image)");
  }
}

}  // namespace

double Filmback::DiagonalMm() const { return std::hypot(width_mm, height_mm); }

const std::vector<Filmback>& FilmbackPresets() {
  // Sizes in mm. Super 35 and 16:9 Digital Film as Unreal's CineCamera defines them (UCineCameraComponent presets).
  static const std::vector<Filmback> presets = {
      {"super35", "Super 35", 24.89, 18.67},
      {"digital-film-16x9", "16:9 Digital Film", 23.76, 13.365},
      {"full-frame", "Full frame (35 mm still)", 36.0, 24.0},
      {"aps-c", "APS-C (Sony/Nikon)", 23.5, 15.6},
      {"micro-four-thirds", "Micro Four Thirds", 17.3, 13.0},
      {"one-inch", "1-inch type", 13.2, 8.8},
      {"one-over-2.3-inch", "1/2.3-inch type (small drones)", 6.17, 4.55},
  };
  return presets;
}

std::optional<Filmback> FindFilmback(std::string_view name) {
  for (const auto& f : FilmbackPresets()) {
    if (f.name == name) return f;
  }
  return std::nullopt;
}

double DefaultCocMm(double sensor_width_mm, double sensor_height_mm) {
  constexpr double kFullFrameDiagonalMm = 43.266615305567875;  // hypot(36, 24)
  return 0.03 * std::hypot(sensor_width_mm, sensor_height_mm) / kFullFrameDiagonalMm;
}

void ValidateFocalLengthMm(double focal_length_mm, const std::string& what) {
  if (!std::isfinite(focal_length_mm) || !(focal_length_mm > 0)) {
    throw InputError(what + ": must be a finite number > 0 mm, got " + Num(focal_length_mm));
  }
}

void ValidateFNumber(double f_number, const std::string& what) {
  if (!std::isfinite(f_number) || !(f_number > 0)) {
    throw InputError(what + ": must be a finite number > 0, got " + Num(f_number));
  }
}

void ValidateFocusDistanceM(double focus_distance_m, double focal_length_mm, const std::string& what) {
  if (std::isnan(focus_distance_m) || focus_distance_m == -kInf) {
    throw InputError(what + ": must be a number of metres or inf");
  }
  if (!(focus_distance_m > 0)) {
    throw InputError(what + ": must be > 0 m, got " + Num(focus_distance_m));
  }
  if (focus_distance_m * kMmPerM <= focal_length_mm) {
    throw InputError(what + ": " + Num(focus_distance_m) + " m is inside the focal length " + Num(focal_length_mm) +
                     " mm (no real image)");
  }
}

double BlurCircleMm(double focal_length_mm, double f_number, double focus_distance_m, double subject_distance_m) {
  ValidateFocalLengthMm(focal_length_mm);
  ValidateFNumber(f_number);
  ValidateFocusDistanceM(focus_distance_m, focal_length_mm);
  ValidateSubjectDistanceM(subject_distance_m, focal_length_mm);
  const double inv_s = 1.0 / focus_distance_m;  // 0 at infinity
  const double inv_d = 1.0 / subject_distance_m;
  return BlurCircleDiameterM(focal_length_mm / kMmPerM, f_number, inv_s, inv_d) * kMmPerM;
}

double MmToPixels(double sensor_mm, double sensor_width_mm, int width_px) {
  if (!(sensor_width_mm > 0) || width_px <= 0) {
    throw InputError("sensor width and image width must be > 0");
  }
  return sensor_mm * static_cast<double>(width_px) / sensor_width_mm;
}

double HyperfocalDistanceM(double focal_length_mm, double f_number, double coc_mm) {
  ValidateFocalLengthMm(focal_length_mm);
  ValidateFNumber(f_number);
  if (!std::isfinite(coc_mm) || !(coc_mm > 0)) {
    throw InputError("acceptable blur (circle of confusion): must be > 0 mm, got " + Num(coc_mm));
  }
  const double h_mm = focal_length_mm * focal_length_mm / (f_number * coc_mm) + focal_length_mm;
  return h_mm / kMmPerM;
}

DepthOfField DepthOfFieldLimits(double focal_length_mm, double f_number, double focus_distance_m, double coc_mm) {
  DepthOfField dof;
  dof.hyperfocal_m = HyperfocalDistanceM(focal_length_mm, f_number, coc_mm);
  ValidateFocusDistanceM(focus_distance_m, focal_length_mm);
  const double h = dof.hyperfocal_m;
  const double f = focal_length_mm / kMmPerM;
  const double s = focus_distance_m;
  if (std::isinf(s)) {
    dof.near_m = h - f;
    dof.far_m = kInf;
    return dof;
  }
  dof.near_m = s * (h - f) / (h + s - 2 * f);
  dof.far_m = s >= h ? kInf : s * (h - f) / (h - s);
  return dof;
}

ImageExtentMm ImageExtentOnSensorMm(double sensor_width_mm, int width_px, int height_px) {
  if (!(sensor_width_mm > 0) || !std::isfinite(sensor_width_mm) || width_px <= 0 || height_px <= 0) {
    throw InputError("sensor fit: the sensor width and the image size must be > 0");
  }
  return {sensor_width_mm, sensor_width_mm * static_cast<double>(height_px) / static_cast<double>(width_px)};
}

double FieldOfViewRad(double sensor_extent_mm, double focal_length_mm) {
  ValidateFocalLengthMm(focal_length_mm);
  if (!std::isfinite(sensor_extent_mm) || !(sensor_extent_mm > 0)) {
    throw InputError("sensor size: must be > 0 mm, got " + Num(sensor_extent_mm));
  }
  return 2.0 * std::atan(sensor_extent_mm / (2.0 * focal_length_mm));
}

double FocalLengthForFieldOfViewMm(double sensor_extent_mm, double field_of_view_rad) {
  if (!(field_of_view_rad > 0) || !(field_of_view_rad < M_PI)) {
    throw InputError("field of view: must be in (0, 180) degrees");
  }
  if (!std::isfinite(sensor_extent_mm) || !(sensor_extent_mm > 0)) {
    throw InputError("sensor size: must be > 0 mm, got " + Num(sensor_extent_mm));
  }
  return sensor_extent_mm / (2.0 * std::tan(field_of_view_rad / 2.0));
}

double MagnificationAt(double focal_length_mm, double subject_distance_m) {
  ValidateFocalLengthMm(focal_length_mm);
  ValidateSubjectDistanceM(subject_distance_m, focal_length_mm);
  const double f = focal_length_mm / kMmPerM;
  return f / (subject_distance_m - f);
}

}  // namespace cinepath
