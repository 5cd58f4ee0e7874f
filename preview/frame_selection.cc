#include "preview/frame_selection.h"

#include <charconv>
#include <string_view>

#include "core/error.h"

namespace cinepath::preview {
namespace {

std::optional<size_t> ParseIndex(std::string_view text) {
  size_t value = 0;
  if (text.empty()) return std::nullopt;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

FrameRange ParseFrameRange(const std::string& text) {
  const size_t dash = text.find('-');
  const std::string_view all(text);
  const auto first = ParseIndex(all.substr(0, dash));
  const auto last = dash == std::string::npos ? first : ParseIndex(all.substr(dash + 1));
  if (!first || !last || *last < *first) {
    throw InputError("--frames: expected A-B with sample indices A <= B (zero-based, inclusive), got '" + text + "'");
  }
  return {*first, *last};
}

Shard ParseShard(const std::string& text) {
  const size_t slash = text.find('/');
  const std::string_view all(text);
  const auto index = slash == std::string::npos ? std::nullopt : ParseIndex(all.substr(0, slash));
  const auto count = slash == std::string::npos ? std::nullopt : ParseIndex(all.substr(slash + 1));
  if (!index || !count || *count == 0 || *index >= *count) {
    throw InputError("--shard: expected i/N with 0 <= i < N, got '" + text + "'");
  }
  return {*index, *count};
}

std::vector<size_t> SelectFrames(size_t num_samples, const FrameSelection& selection) {
  if (num_samples == 0) throw InputError("the plan has no samples to render");
  if (selection.every == 0) throw InputError("--every: must be at least 1");
  const FrameRange range = selection.range.value_or(FrameRange{0, num_samples - 1});
  if (range.last >= num_samples) {
    throw InputError("--frames: " + std::to_string(range.first) + "-" + std::to_string(range.last) +
                     " lies outside the plan's samples 0-" + std::to_string(num_samples - 1));
  }
  std::vector<size_t> frames;
  size_t position = 0;  // index within the every-N selection, for the shard
  for (size_t k = range.first; k <= range.last; k += selection.every, ++position) {
    if (position % selection.shard.count == selection.shard.index) frames.push_back(k);
  }
  return frames;
}

}  // namespace cinepath::preview
