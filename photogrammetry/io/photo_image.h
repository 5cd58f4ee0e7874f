// A photo's pixels as 8-bit sRGB, decoded by the OpenImageIO plugin (exif_gps_abi.h; loaded with dlopen
// on first use like the EXIF reader, so `mesh` without photos never loads OpenImageIO), and the
// encoders of the texture atlas (PNG, JPEG; stb_image_write, which writes the same bytes every run).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace cinepath::photogrammetry {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel (sRGB)

  bool empty() const { return rgb.empty(); }
  const uint8_t* At(int x, int y) const { return &rgb[(size_t(y) * width + x) * 3]; }
  uint8_t* At(int x, int y) { return &rgb[(size_t(y) * width + x) * 3]; }
};

// InputError naming the file when it cannot be decoded; RuntimeError when the plugin is missing.
RgbImage ReadPhotoRgb8(const std::filesystem::path& path);

// Linear RGB at pixel position (x, y) in COLMAP's convention (the centre of the upper-left pixel is
// (0.5, 0.5)): bilinear between the four nearest pixels, each converted from sRGB first; positions
// outside are clamped to the border.
Eigen::Vector3f SampleLinear(const RgbImage& image, double x, double y);

// Linear value of an 8-bit sRGB channel, and back (IEC 61966-2-1; rounded, clamped to [0, 1]).
float LinearFromSrgb(uint8_t value);
uint8_t SrgbFromLinear(float linear);

// Encoded bytes. JPEG `quality` in 1..100 (at 90 and above stb_image_write keeps full-resolution chroma).
std::string EncodePng(const RgbImage& image);
std::string EncodeJpeg(const RgbImage& image, int quality);

}  // namespace cinepath::photogrammetry
