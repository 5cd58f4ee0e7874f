// Ground control points in OpenDroneMap's gcp_list.txt format (docs.opendronemap.org "Ground Control
// Points"; OpenSfM io.read_gcp_list reads the same file):
//
//   <coordinate system>                                   first non-blank, non-comment line
//   geo_x geo_y geo_z im_x im_y image_name [gcp_name] [extras...]
//   ...
//
// Fields are separated by spaces or tabs; blank lines and lines starting with '#' are skipped.
//
// Coordinate systems (only WGS84 ones; converted with GeographicLib, UTM through UTMUPS):
//   * `EPSG:4326`, `EPSG:4979`, `WGS84`, `+proj=longlat +datum=WGS84` (or +ellps=WGS84): geographic,
//     geo_x = LONGITUDE, geo_y = LATITUDE (degrees). This x-then-y order is what ODM reads (its
//     converter uses the traditional GIS order, and ODM's own examples and users' files put the
//     longitude first), not EPSG:4326's official latitude-first axis order. A file whose geo_y is
//     outside [-90, 90] while geo_x is inside is refused with a message saying the columns look
//     swapped.
//   * UTM, geo_x = easting, geo_y = northing (metres): `WGS84 UTM 32N` / `WGS84 UTM 32S` (zone 1..60,
//     hemisphere letter N or S; a bare zone number means north, as OpenSfM), `EPSG:326zz` (north) /
//     `EPSG:327zz` (south), or a PROJ string `+proj=utm +zone=32 [+south] [+north] +datum=WGS84 |
//     +ellps=WGS84 [+units=m] [+no_defs] [+type=crs]` (a PROJ string with any other datum, ellipsoid
//     or parameter is refused).
//   * geo_z: height in metres, WGS84 ellipsoidal unless the caller says it is above mean sea level
//     (EGM96); `NaN` means "no elevation" (ODM allows it): such a point is reported and not used.
//
// Image coordinates: im_x, im_y are pixels of the image named, measured on the images COLMAP
// reconstructed (not on originals of another resolution), with the centre of the top-left pixel at
// (0, 0) as OpenSfM reads them (it normalizes with x + 0.5). cinepath converts to COLMAP's convention
// (upper-left image corner at (0, 0)) by adding 0.5 to both.
//
// Grouping into points: lines with the same gcp_name are observations of one point; lines without a
// name are grouped by their (geo_x, geo_y, geo_z) values, as OpenSfM groups them (NaN heights count as
// equal here). Lines of
// the same name with different coordinates, and a point observed twice in one image, are errors.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace cinepath::photogrammetry {

struct GcpCoordinateSystem {
  enum class Kind { kGeographic, kUtm };
  Kind kind = Kind::kGeographic;
  int utm_zone = 0;         // 1..60 for kUtm
  bool utm_north = true;    // hemisphere for kUtm
  std::string header;       // the first line as written (trimmed)
  std::string description;  // "WGS84 geographic (x = longitude, y = latitude)", "WGS84 UTM zone 32N"
};

struct GcpObservation {
  std::string image_name;
  Eigen::Vector2d pixel_file = Eigen::Vector2d::Zero();    // im_x, im_y as written
  Eigen::Vector2d pixel_colmap = Eigen::Vector2d::Zero();  // COLMAP convention (+0.5)
  std::string where;                                       // "gcp_list.txt: line 4"
};

struct GroundControlPoint {
  std::string name;  // gcp_name, or "gcp<k>" (1-based, in file order) when the file gives none
  bool named_in_file = false;
  double geo_x = 0, geo_y = 0;               // as written
  double lat_deg = 0, lon_deg = 0;           // WGS84
  std::optional<double> geo_z_m;             // unset for NaN ("no elevation")
  std::vector<GcpObservation> observations;  // in file order
  std::string where;                         // first line that names the point
};

struct GcpFile {
  GcpCoordinateSystem crs;
  std::vector<GroundControlPoint> points;  // in order of first appearance
};

// The coordinate-system line on its own. InputError naming `where` for anything unsupported.
GcpCoordinateSystem ParseGcpCoordinateSystem(std::string_view header, const std::string& where);

// InputError naming the file and line for: a missing or unsupported coordinate-system line, fewer
// than 6 fields, a number that does not parse or is infinite (NaN only for geo_z), coordinates
// outside the system's range (latitude, longitude, UTM easting/northing), negative pixel coordinates,
// a name reused with other coordinates, two observations of one point in one image, and a file with
// no GCP line.
GcpFile ParseGcpFile(std::string_view text, const std::string& source);
GcpFile ReadGcpFile(const std::filesystem::path& path);

}  // namespace cinepath::photogrammetry
