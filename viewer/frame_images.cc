#include "viewer/frame_images.h"

#include <system_error>

#include "core/error.h"

namespace cinepath::viewer {

long long FrameIndexFromFileName(const std::string& file_name) {
  // frame_ + six or more digits + .png / .jpg
  const std::string prefix = "frame_";
  if (file_name.rfind(prefix, 0) != 0) return -1;
  const size_t dot = file_name.rfind('.');
  if (dot == std::string::npos || dot < prefix.size() + 6) return -1;
  const std::string digits = file_name.substr(prefix.size(), dot - prefix.size());
  for (char c : digits) {
    if (c < '0' || c > '9') return -1;
  }
  if (digits.size() > 12) return -1;
  return std::stoll(digits);
}

std::map<size_t, FrameImage> FindRenderedFrames(const std::filesystem::path& dir, size_t num_samples) {
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) {
    throw InputError("--frames: " + dir.string() + ": not a folder");
  }
  std::map<size_t, FrameImage> frames;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string name = entry.path().filename().string();
    const long long k = FrameIndexFromFileName(name);
    if (k < 0 || size_t(k) >= num_samples) continue;
    const std::string ext = entry.path().extension().string();
    std::string mime;
    if (ext == ".png") {
      mime = "image/png";
    } else if (ext == ".jpg" || ext == ".jpeg") {
      mime = "image/jpeg";
    } else {
      continue;
    }
    auto it = frames.find(size_t(k));
    // The directory's order is the file system's: prefer PNG, then the smaller name, so the result
    // does not depend on it.
    if (it != frames.end()) {
      const bool keep = it->second.mime_type == "image/png" && mime != "image/png";
      const bool same_kind = it->second.mime_type == mime;
      if (keep || (same_kind && it->second.path.filename().string() < name)) continue;
    }
    frames[size_t(k)] = {entry.path(), mime};
  }
  return frames;
}

}  // namespace cinepath::viewer
