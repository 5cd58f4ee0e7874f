#include "export/mission.h"

#include <algorithm>

namespace cinepath::exporter {

const char* AltitudeRefName(AltitudeRef ref) {
  switch (ref) {
    case AltitudeRef::kRelative: return "relative";
    case AltitudeRef::kAmsl: return "amsl";
    case AltitudeRef::kEllipsoid: return "ellipsoid";
  }
  return "?";
}

double ZoomPercent(const Mission& mission, double focal_length_mm) {
  const double span = mission.max_focal_length_mm - mission.min_focal_length_mm;
  if (!(span > 0)) return 0.0;
  return std::clamp((focal_length_mm - mission.min_focal_length_mm) / span * 100.0, 0.0, 100.0);
}

double FocalLength35mmEquivalent(const Mission& mission, double focal_length_mm) {
  constexpr double kFullFrameDiagonalMm = 43.2666;
  return focal_length_mm * kFullFrameDiagonalMm / mission.sensor_diagonal_mm;
}

double AltitudeIn(const MissionWaypoint& wp, AltitudeRef ref) {
  switch (ref) {
    case AltitudeRef::kRelative: return wp.relative_alt_m;
    case AltitudeRef::kAmsl: return wp.amsl_m;
    case AltitudeRef::kEllipsoid: return wp.ellipsoidal_height_m;
  }
  return wp.relative_alt_m;
}

}  // namespace cinepath::exporter
