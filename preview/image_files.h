// Frames and sheets on disk: PNG (its chunks written here, libdeflate; libpng decodes) and JPEG (libjpeg) hold
// sRGB-encoded 8-bit colour (encoded here, by the sRGB transfer function, rounded), EXR linear half or
// 32-bit float (the OpenEXR library, ZIP-compressed).
// No OpenImageIO: its Debian build brings ~260 shared libraries whose loading took half a second of every
// render's start. Every file is written to a temporary name beside its target and renamed once complete,
// so a failed write leaves no partial file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "preview/render_options.h"
#include "preview/uninitialized_allocator.h"

namespace cinepath::preview {

using ImageBytes = std::vector<uint8_t, UninitializedAllocator<uint8_t>>;

// An 8-bit sRGB image, RGB interleaved, rows from the top.
struct Srgb8Image {
  int width = 0;
  int height = 0;
  ImageBytes rgb;
};

// Linear [0, 1] -> 8-bit sRGB: the transfer function, rounded; 0 for NaN and below, 255 from 1 up.
uint8_t LinearToSrgb8(float linear);
// The same values from a table of the 255 steps' thresholds (a search instead of a pow() per channel);
// EncodeSrgb8 uses it.
uint8_t LinearToSrgb8ByTable(float linear);
// The same for `count` values at once (the table looked up once): out[i] = LinearToSrgb8ByTable(linear[i]).
void LinearToSrgb8ByTable(const float* linear, size_t count, uint8_t* out);
Srgb8Image EncodeSrgb8(const std::vector<Eigen::Vector3f>& rgb_linear, int width, int height);

// Given an image's width and height, a flag per row: the rows its user will read (the rest may be left
// unwritten).
using RowsWanted = std::function<std::vector<uint8_t>(int width, int height)>;

// A PNG or JPEG (told by its first bytes) decoded to 8-bit RGB as stored (grey replicated, alpha dropped;
// libjpeg's default islow IDCT and fancy upsampling). InputError naming `where` when it cannot be.
// With `rows_wanted`, a JPEG's rows it does not flag are left unwritten (skipped: entropy-decoded only,
// and after the last row flagged not decoded at all); every row it flags holds the bytes of a full
// decode. A PNG is decoded in full.
Srgb8Image DecodeSrgb8(const std::vector<uint8_t>& encoded, const std::string& where,
                       const RowsWanted& rows_wanted = nullptr);
// A JPEG decoded by `parts` decoders at once, each a band of rows (the same bytes as one decoder).
Srgb8Image DecodeJpeg(const std::vector<uint8_t>& encoded, const std::string& where, int parts);
// A JPEG decoded by two decoders that split its rows when the second starts (the same bytes as one
// decoder): the first starts at once on the calling thread from the top; the second, a task, starts
// when a thread is free (at once on an idle machine, later when the plan's reading holds the other core,
// never when none frees up before the first ends) and takes the bottom rows from
// JpegSecondBandStart(height, rows the first has taken), so both end together. DecodeSrgb8's JPEG path
// (with `rows_wanted` as there: both decoders end after the last row wanted, and share the rows up to it).
Srgb8Image DecodeJpegShared(const std::vector<uint8_t>& encoded, const std::string& where,
                            const RowsWanted& rows_wanted = nullptr);
// The second decoder's first row (a multiple of 16, not before `first_done`), or `height` when what is
// left is too little to share.
int JpegSecondBandStart(int height, int first_done);

// PNG (the Sub filter, one zlib stream deflated by libdeflate at level 1: the same bytes on any thread
// count) or JPEG (quality 95) from 8-bit sRGB; RuntimeError naming the file when it cannot be written.
void WriteSrgb8Atomic(const std::filesystem::path& path, const Srgb8Image& image);
// EXR (ZIP compression) from linear float channels, interleaved; channel names as given ("R,G,B", "Z").
void WriteExrAtomic(const std::filesystem::path& path, int width, int height, const std::vector<std::string>& channels,
                    const std::vector<float>& values, ExrPixel pixel = ExrPixel::kFloat);

// The bytes of that EXR file (OpenEXR's OutputFile without worker threads: single-part scanline, ZIP,
// channels stored in name order, as `pixel` says; the same bytes for the same input).
std::vector<uint8_t> EncodeExr(int width, int height, const std::vector<std::string>& channels,
                               const std::vector<float>& values, ExrPixel pixel = ExrPixel::kFloat);

// RuntimeError when the labels' font is missing (checked before a run writes anything).
void RequireLabelFont();
// Draws text (DejaVu Sans Mono through stb_truetype, white with a dark shadow) with its top-left corner at (x, y).
// RuntimeError when no font is installed (Debian fonts-dejavu-core).
void DrawText(Srgb8Image* image, int x, int y, int size_px, const std::string& text);

}  // namespace cinepath::preview
