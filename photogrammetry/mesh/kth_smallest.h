// The k-th smallest of many lists of non-negative floats, without joining them: a radix selection,
// for the decimation's band (photogrammetry/mesh/mesh_decimate_qem.cc), which picks the cost below
// which a share of its ~1-3 M queued collapses falls: the band's targets took 28-38 ms with
// std::nth_element on the joined costs, 11-14 ms with this (2.5 M-face bench terrain at 40 %).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cinepath::photogrammetry {

// The k-th smallest (from 0) of the values in `lists`, none negative or NaN: a radix selection on their
// bits (which order as unsigned integers), 11 bits a round, each round's histogram counted per list in
// parallel. The value, not its place, so the same as std::nth_element's on the lists joined.
// k must be below the number of values.
inline float KthSmallest(const std::vector<std::vector<float>>& lists, size_t k) {
  constexpr int kDigitBits = 11;
  constexpr uint32_t kDigits = 1u << kDigitBits;
  uint32_t prefix = 0, prefix_mask = 0;
  for (int shift = 32 - kDigitBits; shift > -kDigitBits; shift -= kDigitBits) {
    const int low = std::max(shift, 0);
    const uint32_t digit_mask = (kDigits - 1) >> (low - shift);
    std::vector<std::vector<size_t>> histograms(lists.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, lists.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
      for (size_t l = range.begin(); l != range.end(); ++l) {
        histograms[l].assign(kDigits, 0);
        for (float value : lists[l]) {
          uint32_t bits;
          std::memcpy(&bits, &value, sizeof bits);
          if ((bits & prefix_mask) == prefix) ++histograms[l][(bits >> low) & digit_mask];
        }
      }
    });
    uint32_t digit = 0;
    for (;; ++digit) {
      size_t count = 0;
      for (const auto& histogram : histograms) count += histogram[digit];
      if (k < count) break;
      k -= count;
    }
    prefix |= digit << low;
    prefix_mask |= digit_mask << low;
  }
  float value;
  std::memcpy(&value, &prefix, sizeof value);
  return value;
}

}  // namespace cinepath::photogrammetry
