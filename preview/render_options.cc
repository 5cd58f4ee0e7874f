#include "preview/render_options.h"

#include <sstream>

#include "core/error.h"

namespace cinepath::preview {

SamplingPreset PresetFor(Quality quality) {
  SamplingPreset preset;
  switch (quality) {
    case Quality::kDraft:
      preset.gather_blur = true;
      preset.texture_lod = true;
      preset.edge_samples = 4;
      // Only the edges a frame shows at a glance: objects, depth steps and strong colour steps (texture
      // detail below this is left to the pinhole ray; bench/RESULTS.md has the PSNR it costs).
      preset.edge_color_step = 0.2f;
      preset.max_samples = 4;
      preset.motion_blur = false;
      break;
    case Quality::kStandard:
      preset.edge_samples = 4;
      preset.samples_per_blur_px2 = 1.0;
      preset.min_blurred_samples = 16;
      preset.max_samples = 128;
      break;
    case Quality::kFinal:
      preset.edge_samples = 16;
      preset.samples_per_blur_px2 = 4.0;
      preset.min_blurred_samples = 64;
      preset.max_samples = 1024;
      break;
  }
  return preset;
}

ImageFormat ParseImageFormat(const std::string& text) {
  if (text == "png") return ImageFormat::kPng;
  if (text == "exr") return ImageFormat::kExr;
  if (text == "jpg" || text == "jpeg") return ImageFormat::kJpg;
  throw InputError("--format: expected png, exr or jpg, got '" + text + "'");
}

ExrPixel ParseExrPixel(const std::string& text) {
  if (text == "half") return ExrPixel::kHalf;
  if (text == "float") return ExrPixel::kFloat;
  throw InputError("--exr-pixel: expected half or float, got '" + text + "'");
}

Shading ParseShading(const std::string& text) {
  if (text == "flat") return Shading::kFlat;
  if (text == "sun") return Shading::kSun;
  throw InputError("--shading: expected flat or sun, got '" + text + "'");
}

Backdrop ParseBackdrop(const std::string& text) {
  if (text == "ground") return Backdrop::kGround;
  if (text == "none") return Backdrop::kNone;
  throw InputError("--backdrop: expected ground or none, got '" + text + "'");
}

SunDirection ParseSunDirection(const std::string& text) {
  SunDirection sun;
  char comma = 0;
  std::istringstream is(text);
  if (!(is >> sun.azimuth_deg >> comma >> sun.elevation_deg) || comma != ',' || !is.eof() ||
      !(sun.elevation_deg > 0 && sun.elevation_deg <= 90) || !(sun.azimuth_deg >= -360 && sun.azimuth_deg <= 360)) {
    throw InputError("--sun: expected AZIMUTH,ELEVATION in degrees (elevation in (0, 90]), got '" + text + "'");
  }
  return sun;
}

const char* FileExtension(ImageFormat format) {
  switch (format) {
    case ImageFormat::kPng: return "png";
    case ImageFormat::kExr: return "exr";
    case ImageFormat::kJpg: return "jpg";
  }
  return "png";
}

}  // namespace cinepath::preview
