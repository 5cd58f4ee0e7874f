#include "photogrammetry/io/gcp_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include <GeographicLib/Constants.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include "core/error.h"
#include "core/file_io.h"
#include "core/text_tokens.h"

namespace cinepath::photogrammetry {
namespace {

std::string Upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::optional<int> ParseInt(std::string_view s) {
  int v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

// A number as ODM/OpenSfM accept it (Python float()): decimal or exponent form; "nan" (any case)
// only where allowed.
std::optional<double> ParseNumber(std::string_view s, bool allow_nan) {
  if (allow_nan && Lower(s) == "nan") return std::numeric_limits<double>::quiet_NaN();
  std::string_view t = s;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double v = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

constexpr const char* kSupported =
    "supported: EPSG:4326, EPSG:4979, WGS84 (x = longitude, y = latitude), 'WGS84 UTM <zone>N|S', EPSG:326<zone> / "
    "EPSG:327<zone>, '+proj=utm +zone=<zone> [+south] +datum=WGS84', '+proj=longlat +datum=WGS84'";

GcpCoordinateSystem Geographic(std::string header) {
  GcpCoordinateSystem crs;
  crs.kind = GcpCoordinateSystem::Kind::kGeographic;
  crs.header = std::move(header);
  crs.description = "WGS84 geographic (x = longitude deg, y = latitude deg, z = height m)";
  return crs;
}

GcpCoordinateSystem Utm(std::string header, int zone, bool north, const std::string& where) {
  if (zone < 1 || zone > 60) {
    throw InputError(Located(where, "UTM zone " + std::to_string(zone) + " outside 1..60"));
  }
  GcpCoordinateSystem crs;
  crs.kind = GcpCoordinateSystem::Kind::kUtm;
  crs.utm_zone = zone;
  crs.utm_north = north;
  crs.header = std::move(header);
  crs.description =
      "WGS84 UTM zone " + std::to_string(zone) + (north ? "N" : "S") + " (x = easting m, y = northing m, z = height m)";
  return crs;
}

GcpCoordinateSystem ParseProjString(const std::vector<std::string_view>& tokens, const std::string& header,
                                    const std::string& where) {
  std::string proj;
  std::optional<int> zone;
  bool south = false, wgs84 = false;
  for (std::string_view raw : tokens) {
    const std::string t = Lower(raw);
    if (t.rfind('+', 0) != 0)
      throw InputError(Located(where, "PROJ string: '" + std::string(raw) + "' is not a +key[=value]"));
    const size_t eq = t.find('=');
    const std::string key = t.substr(1, eq == std::string::npos ? std::string::npos : eq - 1);
    const std::string value = eq == std::string::npos ? "" : t.substr(eq + 1);
    if (key == "proj") {
      proj = value;
    } else if (key == "zone") {
      zone = ParseInt(value);
      if (!zone) throw InputError(Located(where, "PROJ string: +zone='" + value + "' is not a zone number"));
    } else if (key == "south") {
      south = value.empty() || value == "true";
    } else if (key == "north") {
      south = !(value.empty() || value == "true");
    } else if (key == "datum" || key == "ellps") {
      if (value != "wgs84") {
        throw InputError(Located(where, "PROJ string: +" + key + "=" + value + " is not supported (only WGS84; " +
                                            std::string(kSupported) + ")"));
      }
      wgs84 = true;
    } else if (key == "units") {
      if (value != "m") throw InputError(Located(where, "PROJ string: +units=" + value + " is not supported (only m)"));
    } else if (key == "no_defs" || key == "type" || key == "wktext") {
      // no effect on the coordinates
    } else {
      throw InputError(Located(where, "PROJ string: +" + key + " is not supported (" + std::string(kSupported) + ")"));
    }
  }
  if (!wgs84)
    throw InputError(
        Located(where, "PROJ string without +datum=WGS84 or +ellps=WGS84 (" + std::string(kSupported) + ")"));
  if (proj == "utm") {
    if (!zone) throw InputError(Located(where, "PROJ string: +proj=utm without +zone"));
    return Utm(header, *zone, !south, where);
  }
  if (proj == "longlat" || proj == "latlong" || proj == "lonlat") return Geographic(header);
  throw InputError(
      Located(where, "PROJ string: +proj=" + proj + " is not supported (" + std::string(kSupported) + ")"));
}

}  // namespace

GcpCoordinateSystem ParseGcpCoordinateSystem(std::string_view header_view, const std::string& where) {
  const auto tokens = WhitespaceTokens(header_view);
  std::string header;
  for (size_t i = 0; i < tokens.size(); ++i) header += (i ? " " : "") + std::string(tokens[i]);
  if (tokens.empty())
    throw InputError(Located(where, "missing coordinate-system line (" + std::string(kSupported) + ")"));
  const std::string first = Upper(tokens[0]);
  if (tokens[0].front() == '+' || (tokens[0].front() == '\'' && tokens[0].size() > 1)) {
    // ODM strips quotes around a PROJ string.
    std::string unquoted = header;
    unquoted.erase(std::remove(unquoted.begin(), unquoted.end(), '\''), unquoted.end());
    return ParseProjString(WhitespaceTokens(unquoted), header, where);
  }
  if (first.rfind("EPSG:", 0) == 0 && tokens.size() == 1) {
    const auto code = ParseInt(std::string_view(tokens[0]).substr(5));
    if (!code) throw InputError(Located(where, "'" + header + "': not an EPSG code"));
    if (*code == 4326 || *code == 4979) return Geographic(header);
    if (*code >= 32601 && *code <= 32660) return Utm(header, *code - 32600, true, where);
    if (*code >= 32701 && *code <= 32760) return Utm(header, *code - 32700, false, where);
    throw InputError(
        Located(where, "EPSG:" + std::to_string(*code) + " is not supported (" + std::string(kSupported) + ")"));
  }
  if (first == "WGS84" && tokens.size() == 1) return Geographic(header);
  if (first == "WGS84" && tokens.size() == 3 && Upper(tokens[1]) == "UTM") {
    std::string zone_text = Upper(tokens[2]);
    bool north = true;
    if (!zone_text.empty() && (zone_text.back() == 'N' || zone_text.back() == 'S')) {
      north = zone_text.back() == 'N';
      zone_text.pop_back();
    }
    const auto zone = ParseInt(zone_text);
    if (!zone)
      throw InputError(Located(where, "'" + header + "': expected 'WGS84 UTM <zone>N' or 'WGS84 UTM <zone>S'"));
    return Utm(header, *zone, north, where);
  }
  throw InputError(Located(where, "unsupported coordinate system '" + header + "' (" + std::string(kSupported) + ")"));
}

GcpFile ParseGcpFile(std::string_view text, const std::string& source) {
  GcpFile file;
  bool have_header = false;
  std::map<std::string, size_t> by_name;  // gcp_name or coordinate text -> index into points
  std::vector<std::set<std::string>> images_of(0);
  int unnamed = 0;
  ForEachDataLine(text, [&](std::string_view line, size_t line_number, const std::vector<std::string_view>& tokens) {
    const std::string where = source + ": line " + std::to_string(line_number);
    if (!have_header) {
      file.crs = ParseGcpCoordinateSystem(line, where);
      have_header = true;
      return;
    }
    if (tokens.size() < 6) {
      throw InputError(Located(where, "expected 'geo_x geo_y geo_z im_x im_y image_name [gcp_name]', found " +
                                          std::to_string(tokens.size()) + " field" + (tokens.size() == 1 ? "" : "s")));
    }
    const char* names[5] = {"geo_x", "geo_y", "geo_z", "im_x", "im_y"};
    double v[5];
    for (int k = 0; k < 5; ++k) {
      const auto value = ParseNumber(tokens[k], k == 2);
      if (!value) {
        throw InputError(Located(where, std::string(names[k]) + ": '" + std::string(tokens[k]) +
                                            "' is not a finite number" + (k == 2 ? " (or NaN for no elevation)" : "")));
      }
      v[k] = *value;
    }
    if (v[3] < -0.5 || v[4] < -0.5) {
      throw InputError(Located(where, "im_x, im_y: (" + std::string(tokens[3]) + ", " + std::string(tokens[4]) +
                                          ") is outside the image (pixel coordinates start at 0)"));
    }
    double lat = 0, lon = 0;
    if (file.crs.kind == GcpCoordinateSystem::Kind::kGeographic) {
      lon = v[0];
      lat = v[1];
      if (std::abs(lat) > 90) {
        throw InputError(
            Located(where, "geo_y (latitude) " + std::string(tokens[1]) + " outside [-90, 90]" +
                               (std::abs(v[0]) <= 90 ? "; with " + file.crs.header +
                                                           " geo_x is the longitude and geo_y the latitude "
                                                           "(the columns look swapped)"
                                                     : std::string())));
      }
      if (lon < -180 || lon > 360) {
        throw InputError(Located(where, "geo_x (longitude) " + std::string(tokens[0]) + " outside [-180, 360]"));
      }
      lon = std::remainder(lon, 360.0);
    } else {
      try {
        GeographicLib::UTMUPS::Reverse(file.crs.utm_zone, file.crs.utm_north, v[0], v[1], lat, lon);
      } catch (const GeographicLib::GeographicErr& e) {
        throw InputError(Located(where, "easting " + std::string(tokens[0]) + ", northing " + std::string(tokens[1]) +
                                            " is not a valid position in " + file.crs.description + ": " + e.what()));
      }
    }
    const std::string image(tokens[5]);
    const bool named = tokens.size() >= 7;
    // Unnamed lines are one point when their coordinates are equal as numbers (NaN heights equal).
    char coordinate_key[96];
    std::snprintf(coordinate_key, sizeof(coordinate_key), "%.17g %.17g %.17g", v[0], v[1],
                  std::isfinite(v[2]) ? v[2] : std::numeric_limits<double>::infinity());
    const std::string key = named ? "name:" + std::string(tokens[6]) : "xyz:" + std::string(coordinate_key);
    auto it = by_name.find(key);
    if (it == by_name.end()) {
      GroundControlPoint p;
      p.named_in_file = named;
      p.name = named ? std::string(tokens[6]) : "gcp" + std::to_string(++unnamed);
      p.geo_x = v[0];
      p.geo_y = v[1];
      p.lat_deg = lat;
      p.lon_deg = lon;
      if (std::isfinite(v[2])) p.geo_z_m = v[2];
      p.where = where;
      it = by_name.emplace(key, file.points.size()).first;
      file.points.push_back(std::move(p));
      images_of.emplace_back();
    } else {
      const GroundControlPoint& p = file.points[it->second];
      const bool same_z = p.geo_z_m ? (std::isfinite(v[2]) && *p.geo_z_m == v[2]) : !std::isfinite(v[2]);
      if (p.geo_x != v[0] || p.geo_y != v[1] || !same_z) {
        throw InputError(Located(where, "GCP '" + p.name + "' has other coordinates here than on " + p.where));
      }
    }
    GroundControlPoint& p = file.points[it->second];
    if (!images_of[it->second].insert(image).second) {
      throw InputError(Located(where, "GCP '" + p.name + "' is already observed in image '" + image + "'"));
    }
    GcpObservation o;
    o.image_name = image;
    o.pixel_file = {v[3], v[4]};
    o.pixel_colmap = {v[3] + 0.5, v[4] + 0.5};
    o.where = where;
    p.observations.push_back(std::move(o));
  });
  if (!have_header) throw InputError(Located(source, "empty: expected a coordinate-system line, then GCP lines"));
  if (file.points.empty()) throw InputError(Located(source, "no GCP lines after the coordinate system"));
  return file;
}

GcpFile ReadGcpFile(const std::filesystem::path& path) { return ParseGcpFile(ReadFileToString(path), path.string()); }

}  // namespace cinepath::photogrammetry
