#include "photogrammetry/io/photo_image.h"

#include <algorithm>
#include <array>
#include <cmath>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "core/error.h"
#include "core/plugin.h"
#include "photogrammetry/io/exif_gps_abi.h"

namespace cinepath::photogrammetry {
namespace {

unsigned char* AllocInVector(void* context, size_t bytes) {
  auto* v = static_cast<std::vector<uint8_t>*>(context);
  v->resize(bytes);
  return v->data();
}

struct SrgbTables {
  std::array<float, 256> to_linear{};
  std::array<uint8_t, 4097> from_linear{};  // linear in steps of 1/4096
  SrgbTables() {
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      to_linear[i] = float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
    }
    for (int i = 0; i <= 4096; ++i) {
      const double x = i / 4096.0;
      const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
      from_linear[i] = uint8_t(std::lround(std::clamp(s, 0.0, 1.0) * 255));
    }
  }
};
const SrgbTables& Tables() {
  static const SrgbTables tables;
  return tables;
}

void AppendToString(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

RgbImage ReadPhotoRgb8(const std::filesystem::path& path) {
  auto read = reinterpret_cast<CinepathImageReadRgb8Fn>(
      LoadPluginSymbol(kCinepathExifPluginFile, kCinepathImageReadRgb8Symbol));
  RgbImage image;
  std::array<char, 512> error{};
  if (!read(path.c_str(), &image.rgb, AllocInVector, &image.width, &image.height, error.data(), error.size())) {
    throw InputError(Located(path.string(), std::string("cannot read the photo: ") + error.data()));
  }
  return image;
}

float LinearFromSrgb(uint8_t value) { return Tables().to_linear[value]; }

uint8_t SrgbFromLinear(float linear) {
  // Interpolating the table would cost more than it gains: 1/4096 steps are finer than 8-bit sRGB
  // everywhere but in the darkest values, where the linear segment is exact to the step anyway.
  const float x = std::clamp(linear, 0.0f, 1.0f) * 4096.0f;
  return Tables().from_linear[size_t(std::lround(x))];
}

Eigen::Vector3f SampleLinear(const RgbImage& image, double x, double y) {
  const auto& lin = Tables().to_linear;
  const double fx = std::clamp(x - 0.5, 0.0, double(image.width - 1));
  const double fy = std::clamp(y - 0.5, 0.0, double(image.height - 1));
  const int x0 = std::min(int(fx), image.width - 1), y0 = std::min(int(fy), image.height - 1);
  const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
  const float wx = float(fx - x0), wy = float(fy - y0);
  const uint8_t *a = image.At(x0, y0), *b = image.At(x1, y0), *c = image.At(x0, y1), *d = image.At(x1, y1);
  Eigen::Vector3f out;
  for (int k = 0; k < 3; ++k) {
    out[k] = (1 - wy) * ((1 - wx) * lin[a[k]] + wx * lin[b[k]]) + wy * ((1 - wx) * lin[c[k]] + wx * lin[d[k]]);
  }
  return out;
}

std::string EncodePng(const RgbImage& image) {
  std::string out;
  if (!stbi_write_png_to_func(AppendToString, &out, image.width, image.height, 3, image.rgb.data(), image.width * 3)) {
    throw RuntimeError("texture: PNG encoding failed");
  }
  return out;
}

std::string EncodeJpeg(const RgbImage& image, int quality) {
  std::string out;
  if (!stbi_write_jpg_to_func(AppendToString, &out, image.width, image.height, 3, image.rgb.data(),
                              std::clamp(quality, 1, 100))) {
    throw RuntimeError("texture: JPEG encoding failed");
  }
  return out;
}

}  // namespace cinepath::photogrammetry
