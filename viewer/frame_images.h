// `view --frames DIR`: the frames `cinepath render` wrote (frame_%06d.png / .jpg, k = sample index)
// that the page shows in its camera view instead of the live picture when one exists for the sample.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

namespace cinepath::viewer {

struct FrameImage {
  std::filesystem::path path;
  std::string mime_type;  // "image/png" or "image/jpeg"
};

// The frames of samples 0 .. num_samples-1 found in `dir`, by sample index (PNG preferred over JPEG
// when both exist). InputError ("--frames: <dir>: not a folder") when `dir` is not a folder; a folder
// without frames gives an empty map.
std::map<size_t, FrameImage> FindRenderedFrames(const std::filesystem::path& dir, size_t num_samples);

// "frame_000042.png" -> 42; nullopt-like -1 for any other name.
long long FrameIndexFromFileName(const std::string& file_name);

}  // namespace cinepath::viewer
