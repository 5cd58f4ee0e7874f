// What `cinepath render` is asked for (cli/cmd_render.cc binds its flags onto this), and the quality
// presets with the figures they were tuned to (docs/render.md, "Presets"; bench/RESULTS.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/quality.h"
#include "preview/frame_selection.h"

namespace cinepath::preview {

enum class Shading { kFlat, kSun };
enum class ImageFormat { kPng, kExr, kJpg };
// How an EXR stores its values: 16-bit half float (the usual choice for a picture in compositing:
// 11 significant bits, a relative rounding error under 2^-11, finite up to 65,504; half the bytes before
// compression, and ZIP compresses it where a float's noisy low bits do not: a rendered 320 x 180 frame
// takes 190 kB against 669 kB, and its ZIP half the time) or 32-bit float (data such as
// depth, whose metres need more than 11 bits).
enum class ExrPixel { kHalf, kFloat };
enum class Exposure { kFixed, kPhysical };
// Past the mesh's edge: kGround continues the ground as a plane at the height of the mesh's border,
// in the border's colour, hazed with distance (docs/render.md, "The horizon"); kNone leaves the world
// ending there (rays below the horizon that miss the mesh see a flat grey, at infinite depth).
enum class Backdrop { kGround, kNone };
// The extra images beside each frame, described in preview/aov.h's AovTable.
enum class Aov { kDepth, kBlur, kMask };

// How many rays a pixel gets. A pinhole pre-pass finds each pixel's depth, and so its blur and its
// motion in pixels; a pixel sharp and still gets one ray (edge_samples where the pre-pass sees an
// edge), a blurred or moving one samples_per_blur_px2 per pixel of its blur (or streak) area, at least
// min_blurred_samples, at most max_samples.
struct SamplingPreset {
  bool gather_blur = false;  // draft: no lens rays; a depth-aware gather blur of the pinhole image
  // draft: the pinhole pass reads each texture at the level of its pyramid the pixel's footprint spans
  // (preview/texture.h), not one texel of the full image
  bool texture_lod = false;
  int edge_samples = 4;
  // A colour step (linear, any channel) between neighbours above this marks both as an edge; a step in
  // depth over 2 % or another object always does.
  float edge_color_step = 0.08f;
  double samples_per_blur_px2 = 1.0;
  int min_blurred_samples = 8;
  int max_samples = 64;
  int min_samples = 1;  // every pixel gets at least this many (a converged reference: --min-spp)
  bool motion_blur = true;
  // The lens rays' noise filtered away (preview/denoiser.h): off in every preset, `--denoise` turns it on.
  bool denoise = false;
};

SamplingPreset PresetFor(Quality quality);

// The levels of a texture's pyramid built for a preset with texture_lod: down to 1/64 of the image's side
// (a 4096² atlas to 64², a texel of 64² of the image's). A coarser level would average rows no face reads
// (the coarsest level's one row is the whole image's), and they would have to be decoded too.
constexpr int kTextureLevels = 7;

struct SunDirection {
  double azimuth_deg = 135;  // compass, clockwise from north
  double elevation_deg = 45;
};

struct RenderOptions {
  std::filesystem::path output_dir;
  FrameSelection frames;
  Quality quality = Quality::kStandard;
  std::optional<int> max_samples;  // --spp: the cap on rays per pixel (overrides the preset's)
  std::optional<int> min_samples;  // --min-spp: rays for every pixel at least (raises the cap to it)
  bool denoise = false;            // --denoise: the lens rays' noise filtered (preview/denoiser.h)
  ImageFormat format = ImageFormat::kPng;
  ExrPixel exr_pixel = ExrPixel::kHalf;  // --exr-pixel: the frames' values in an EXR (the AOVs are always float)
  std::optional<int> width_px;           // the aspect of the plan's camera is kept
  Shading shading = Shading::kFlat;
  SunDirection sun;
  std::optional<int64_t> sun_time_unix_s;  // --sun-time: the sun of that moment at the scene's origin
  Exposure exposure = Exposure::kFixed;
  double iso = 100;  // --exposure physical: relative exposure t * ISO / N^2, 1 at 1/50 s, ISO 100, f/4
  Backdrop backdrop = Backdrop::kGround;
  std::vector<Aov> aovs;  // --aov: the extra images beside each frame (preview/aov.h), in AovTable's order
  bool overlay = false;
  std::optional<std::filesystem::path> contact_sheet;
  std::optional<std::filesystem::path> video;
};

// "png" | "exr" | "jpg" -> ImageFormat, etc.; InputError naming the flag otherwise (the quality's parser
// is core/quality.h's ParseQuality).
ImageFormat ParseImageFormat(const std::string& text);
ExrPixel ParseExrPixel(const std::string& text);
Shading ParseShading(const std::string& text);
Backdrop ParseBackdrop(const std::string& text);
// "AZ,EL" in degrees; InputError naming `--sun`.
SunDirection ParseSunDirection(const std::string& text);

const char* FileExtension(ImageFormat format);

}  // namespace cinepath::preview
