// Frames and sheets on disk (OpenImageIO): PNG and JPEG hold sRGB-encoded 8-bit colour (encoded here,
// by the sRGB transfer function, rounded), EXR linear 32-bit float. Every file is written to a
// temporary name beside its target and renamed once complete, so a failed write leaves no partial file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "preview/render_options.h"

namespace cinepath::preview {

// An 8-bit sRGB image, RGB interleaved, rows from the top.
struct Srgb8Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgb;
};

uint8_t LinearToSrgb8(float linear);
Srgb8Image EncodeSrgb8(const std::vector<Eigen::Vector3f>& rgb_linear, int width, int height);

// PNG or JPEG (quality 95) from 8-bit sRGB; RuntimeError naming the file when it cannot be written.
void WriteSrgb8Atomic(const std::filesystem::path& path, const Srgb8Image& image);
// EXR (ZIP compression) from linear float channels, interleaved; channel names as given ("R,G,B", "Z").
void WriteExrAtomic(const std::filesystem::path& path, int width, int height, const std::vector<std::string>& channels,
                    const std::vector<float>& values);

// RuntimeError when the labels' font is missing (checked before a run writes anything).
void RequireLabelFont();
// Draws text (DejaVu Sans Mono, white with a dark shadow) with its top-left corner at (x, y).
// RuntimeError when no font is installed (Debian fonts-dejavu-core).
void DrawText(Srgb8Image* image, int x, int y, int size_px, const std::string& text);

}  // namespace cinepath::preview
