// EGM96 geoid undulation from the grid Debian's proj-data ships (/usr/share/proj/egm96_15.gtx),
// and the AMSL <-> ellipsoidal height conversions every exporter and reader uses.
//
// N is the geoid height above the WGS84 ellipsoid: h_ellipsoidal = H_amsl + N.
// The .gtx grid: big-endian header of 4 doubles (lat0, lon0, dlat, dlon, degrees) and 2 int32 (rows,
// cols), then rows*cols big-endian float32 undulations in metres, row 0 southernmost, column 0 at
// lon0. Interpolation is bilinear, wrapping in longitude; agrees with PROJ's vgridshift to ~2 mm.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cinepath {

class Egm96Geoid {
 public:
  // Loads a .gtx grid; InputError naming the file on a missing or malformed grid.
  explicit Egm96Geoid(const std::filesystem::path& gtx_path);

  // The process-wide grid: $CINEPATH_EGM96_GTX if set, else /usr/share/proj/egm96_15.gtx.
  // Loaded once, on first use.
  static const Egm96Geoid& Default();
  static std::filesystem::path DefaultPath();

  // Geoid undulation N in metres at (lat, lon) degrees. Latitude is clamped to [-90, 90];
  // longitude wraps. InputError for non-finite input.
  double UndulationM(double lat_deg, double lon_deg) const;

  double EllipsoidalFromAmslM(double lat_deg, double lon_deg, double amsl_m) const {
    return amsl_m + UndulationM(lat_deg, lon_deg);
  }
  double AmslFromEllipsoidalM(double lat_deg, double lon_deg, double ellipsoidal_m) const {
    return ellipsoidal_m - UndulationM(lat_deg, lon_deg);
  }

 private:
  double lat0_deg_, lon0_deg_, dlat_deg_, dlon_deg_;
  int rows_, cols_;
  std::vector<float> grid_m_;  // row-major, row 0 southernmost
};

}  // namespace cinepath
