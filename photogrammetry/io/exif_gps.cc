#include "photogrammetry/io/exif_gps.h"

#include <array>
#include <cmath>

#include "core/error.h"
#include "core/number_format.h"
#include "core/plugin.h"
#include "photogrammetry/io/exif_gps_abi.h"

namespace cinepath::photogrammetry {
namespace {

std::string Trim(const std::string& s) {
  const size_t b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const size_t e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

struct SensorEntry {
  const char* make;
  const char* model;
  double width_mm;
};

// Sensor widths of common survey drones' cameras.
constexpr std::array<SensorEntry, 6> kSensors = {{
    {"DJI", "FC300S", 6.317},  // Phantom 3 Advanced (value COLMAP's EXIF prior implies: 914.3 px at 1600)
    {"DJI", "FC300X", 6.317},  // Phantom 3 Professional, same 1/2.3" sensor
    {"DJI", "FC6310", 13.2},   // Phantom 4 Pro, 1"
    {"DJI", "FC6310S", 13.2},  // Phantom 4 Pro V2, 1"
    {"DJI", "L1D-20c", 13.2},  // Mavic 2 Pro (Hasselblad), 1"
    {"DJI", "FC6510", 13.2},   // Zenmuse X4S, 1"
}};

}  // namespace

ExifInfo ReadExif(const std::filesystem::path& image_path) {
  auto read = reinterpret_cast<CinepathExifReadFn>(LoadPluginSymbol(kCinepathExifPluginFile, kCinepathExifReadSymbol));
  CinepathExifRecord record;
  std::array<char, 512> error{};
  if (!read(image_path.c_str(), &record, error.data(), error.size())) {
    throw InputError(Located(image_path.string(), std::string("cannot read EXIF: ") + error.data()));
  }
  if (record.abi_version != kCinepathExifAbiVersion) {
    throw RuntimeError("EXIF plugin ABI version " + std::to_string(record.abi_version) + ", expected " +
                       std::to_string(kCinepathExifAbiVersion));
  }
  ExifInfo info;
  info.file_name = image_path.filename().string();
  info.has_gps = record.has_gps != 0;
  info.lat_deg = record.lat_deg;
  info.lon_deg = record.lon_deg;
  info.alt_m = record.alt_m;
  if (record.has_focal_length) info.focal_length_mm = record.focal_length_mm;
  if (record.focal_length_35mm_mm > 0) info.focal_length_35mm_mm = record.focal_length_35mm_mm;
  info.width_px = record.width_px;
  info.height_px = record.height_px;
  info.make = Trim(record.make);
  info.model = Trim(record.model);
  if (info.has_gps && (std::abs(info.lat_deg) > 90 || !std::isfinite(info.lon_deg) || !std::isfinite(info.alt_m))) {
    throw InputError(Located(image_path.string(), "EXIF GPS position out of range"));
  }
  return info;
}

std::vector<ExifInfo> ReadExifFolder(const std::filesystem::path& images_dir, const std::vector<std::string>& names) {
  if (!std::filesystem::is_directory(images_dir)) {
    throw InputError(Located(images_dir.string(), "not a directory (`images_dir`)"));
  }
  std::vector<ExifInfo> out;
  for (const std::string& name : names) {
    const auto path = images_dir / name;
    if (!std::filesystem::is_regular_file(path)) continue;
    ExifInfo info = ReadExif(path);
    info.file_name = name;
    out.push_back(std::move(info));
  }
  return out;
}

std::vector<ImageReference> ReferencesFromExif(const std::filesystem::path& images_dir,
                                               const std::vector<ExifInfo>& exif) {
  std::vector<ImageReference> refs;
  for (const ExifInfo& e : exif) {
    if (!e.has_gps) continue;
    refs.push_back({e.file_name, e.lat_deg, e.lon_deg, e.alt_m, (images_dir / e.file_name).string() + ": EXIF"});
  }
  return refs;
}

std::optional<double> KnownSensorWidthMm(const std::string& make, const std::string& model) {
  for (const SensorEntry& s : kSensors) {
    if (make == s.make && model == s.model) return s.width_mm;
  }
  return std::nullopt;
}

std::optional<FocalPrior> FocalPriorFromExif(const ExifInfo& exif, double camera_width_px,
                                             std::optional<double> sensor_width_mm) {
  if (exif.focal_length_mm) {
    std::optional<double> width = sensor_width_mm;
    std::string width_source = "given";
    if (!width) {
      width = KnownSensorWidthMm(exif.make, exif.model);
      width_source = "built-in table for " + exif.make + " " + exif.model;
    }
    if (width && *width > 0) {
      return FocalPrior{*exif.focal_length_mm / *width * camera_width_px,
                        "EXIF FocalLength " + FormatFixed(*exif.focal_length_mm, 3) + " mm, sensor width " +
                            FormatFixed(*width, 3) + " mm (" + width_source + "), " + FormatFixed(camera_width_px, 0) +
                            " px wide"};
    }
  }
  if (exif.focal_length_35mm_mm) {
    return FocalPrior{*exif.focal_length_35mm_mm / 36.0 * camera_width_px,
                      "EXIF FocalLengthIn35mmFilm " + FormatFixed(*exif.focal_length_35mm_mm, 1) +
                          " mm (36 mm frame), " + FormatFixed(camera_width_px, 0) + " px wide"};
  }
  return std::nullopt;
}

}  // namespace cinepath::photogrammetry
