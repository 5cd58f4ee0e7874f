// GPS position and focal length from the EXIF of an images folder, through the OpenImageIO plugin
// (exif_gps_abi.h; loaded with dlopen on first use, so commands that never read EXIF never pay for
// OpenImageIO).
//
// Focal length in pixels for a camera `width_px` wide:
//   f_px = FocalLength_mm / sensor_width_mm * width_px
// with the sensor width from, in order: the caller (--sensor-width-mm), a small built-in table of
// drone cameras (Exif Model), else the 35 mm-equivalent focal length: f_px = f35_mm / 36 * width_px.
// Example: DJI FC300S (Phantom 3), 3.61 mm on a 6.317 mm-wide sensor, 1600 px wide -> 914.3 px.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "photogrammetry/io/refs_file.h"

namespace cinepath::photogrammetry {

struct ExifInfo {
  std::string file_name;  // relative to the images folder
  bool has_gps = false;
  double lat_deg = 0, lon_deg = 0, alt_m = 0;  // alt as GPSAltitude says (datum: see georeference_model.h)
  std::optional<double> focal_length_mm;
  std::optional<double> focal_length_35mm_mm;
  int width_px = 0, height_px = 0;
  std::string make, model;
};

// One image. InputError naming the file when it cannot be read; RuntimeError when the plugin is missing.
ExifInfo ReadExif(const std::filesystem::path& image_path);

// Every image of `names` (paths relative to `images_dir`, as COLMAP stores them) that exists. Images
// that do not exist are skipped; unreadable ones are an InputError.
std::vector<ExifInfo> ReadExifFolder(const std::filesystem::path& images_dir, const std::vector<std::string>& names);

// References from the images that carry GPS; `where` reads "<dir>/<name>: EXIF".
std::vector<ImageReference> ReferencesFromExif(const std::filesystem::path& images_dir,
                                               const std::vector<ExifInfo>& exif);

// Built-in sensor widths (mm) by EXIF Make/Model; nullopt when unknown.
std::optional<double> KnownSensorWidthMm(const std::string& make, const std::string& model);

struct FocalPrior {
  double focal_px = 0;
  std::string source;  // how it was derived, for scene.json
};
// nullopt when the EXIF has no usable focal length.
std::optional<FocalPrior> FocalPriorFromExif(const ExifInfo& exif, double camera_width_px,
                                             std::optional<double> sensor_width_mm);

}  // namespace cinepath::photogrammetry
