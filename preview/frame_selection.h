// Which of a plan's frames a render run draws: `--frames A-B` (inclusive sample indices), then
// `--every N` (every N-th of those, starting at A), then `--shard i/N` (every N-th of the selected
// frames starting at the i-th, 0-based). Shards 0..N-1 are disjoint and together give the whole
// selection, so N machines (GNU parallel, a Slurm array, make -j) render one run between them.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace cinepath::preview {

struct FrameRange {
  size_t first = 0;
  size_t last = 0;  // inclusive
};

struct Shard {
  size_t index = 0;  // 0-based
  size_t count = 1;
};

struct FrameSelection {
  std::optional<FrameRange> range;  // absent = every sample
  size_t every = 1;
  Shard shard;
};

// "A-B" with A <= B (or a single "A"); InputError naming `--frames` otherwise.
FrameRange ParseFrameRange(const std::string& text);
// "i/N" with 0 <= i < N; InputError naming `--shard` otherwise.
Shard ParseShard(const std::string& text);

// The sample indices to render, increasing. InputError when the range lies outside the plan's
// num_samples, or `every` is 0.
std::vector<size_t> SelectFrames(size_t num_samples, const FrameSelection& selection);

}  // namespace cinepath::preview
