#include "preview/image_files.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "core/error.h"

namespace cinepath::preview {
namespace {

namespace fs = std::filesystem;

// "DIR/.name.tmp<pid>.ext": the extension tells OpenImageIO the format.
fs::path TempPathFor(const fs::path& target) {
  return target.parent_path() /
         ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) + target.extension().string());
}

void WriteBufferAtomic(const fs::path& path, OIIO::ImageBuf& buffer, OIIO::TypeDesc type) {
  const fs::path temp = TempPathFor(path);
  if (!buffer.write(temp.string(), type)) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw RuntimeError(path.string() + ": cannot write: " + buffer.geterror());
  }
  std::error_code error;
  fs::rename(temp, path, error);
  if (error) {
    fs::remove(temp, error);
    throw RuntimeError(path.string() + ": cannot write: " + error.message());
  }
}

const std::string& FontPath() {
  static const std::string path = [] {
    for (const char* candidate :
         {"/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf", "/usr/share/fonts/TTF/DejaVuSansMono.ttf",
          "/usr/share/fonts/dejavu/DejaVuSansMono.ttf"}) {
      if (fs::exists(candidate)) return std::string(candidate);
    }
    return std::string();
  }();
  return path;
}

}  // namespace

uint8_t LinearToSrgb8(float linear) {
  if (!(linear > 0)) return 0;
  if (linear >= 1) return 255;
  const float encoded = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1 / 2.4f) - 0.055f;
  return uint8_t(std::lround(encoded * 255));
}

Srgb8Image EncodeSrgb8(const std::vector<Eigen::Vector3f>& rgb_linear, int width, int height) {
  Srgb8Image image{width, height, std::vector<uint8_t>(size_t(width) * height * 3)};
  for (size_t i = 0; i < rgb_linear.size(); ++i) {
    for (int c = 0; c < 3; ++c) image.rgb[3 * i + c] = LinearToSrgb8(rgb_linear[i][c]);
  }
  return image;
}

void WriteSrgb8Atomic(const fs::path& path, const Srgb8Image& image) {
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  spec.attribute("CompressionQuality", 95);
  spec.attribute("png:compressionLevel", 3);  // zlib level: a third of level 6's time, 3 % larger
  spec.attribute("Software", "cinepath render");
  OIIO::ImageBuf buffer(spec, const_cast<uint8_t*>(image.rgb.data()));
  WriteBufferAtomic(path, buffer, OIIO::TypeDesc::UINT8);
}

void WriteExrAtomic(const fs::path& path, int width, int height, const std::vector<std::string>& channels,
                    const std::vector<float>& values) {
  OIIO::ImageSpec spec(width, height, int(channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = channels;
  spec.attribute("compression", "zip");
  spec.attribute("Software", "cinepath render");
  // OpenImageIO stamps the wall-clock time into files that carry no DateTime: a fixed one keeps the
  // bytes the same from run to run (the ZIP writer's 1980 epoch, as in the KMZ).
  spec.attribute("DateTime", "1980:01:01 00:00:00");
  OIIO::ImageBuf buffer(spec, const_cast<float*>(values.data()));
  WriteBufferAtomic(path, buffer, OIIO::TypeDesc::FLOAT);
}

void RequireLabelFont() {
  if (FontPath().empty()) {
    throw RuntimeError("labels need the DejaVu Sans Mono font (Debian package fonts-dejavu-core)");
  }
}

void DrawText(Srgb8Image* image, int x, int y, int size_px, const std::string& text) {
  RequireLabelFont();
  OIIO::ImageSpec spec(image->width, image->height, 3, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf buffer(spec, image->rgb.data());
  const float shadow[3] = {0.0f, 0.0f, 0.0f}, white[3] = {1.0f, 1.0f, 1.0f};
  const int baseline = y + size_px;
  OIIO::ImageBufAlgo::render_text(buffer, x + 1, baseline + 1, text, size_px, FontPath(), shadow);
  OIIO::ImageBufAlgo::render_text(buffer, x, baseline, text, size_px, FontPath(), white);
}

}  // namespace cinepath::preview
