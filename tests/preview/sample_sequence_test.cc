#include "preview/sample_sequence.h"

#include <cmath>
#include <set>

#include <gtest/gtest.h>

namespace cinepath::preview {
namespace {

// Owen scrambling keeps the (0,2)-sequence's stratification: the first 2^k lens samples of a pixel fall one
// in each of 2^k equal intervals of either axis, and in each of the 2^k cells of any dyadic grid
// 2^a x 2^(k - a); pixels get different points.
TEST(SampleSequence, OwenScrambledLensSamplesStayStratified) {
  for (uint32_t x : {0u, 7u, 631u}) {
    const SampleSequence sequence(90, x, 17);
    for (int k : {2, 4, 6}) {
      const int n = 1 << k;
      for (int a = 0; a <= k; ++a) {
        std::set<std::pair<int, int>> cells;
        for (int i = 0; i < n; ++i) {
          const PixelSample s = sequence.Get(uint32_t(i));
          ASSERT_TRUE(s.lens_u >= 0 && s.lens_u < 1 && s.lens_v >= 0 && s.lens_v < 1);
          cells.insert({int(std::floor(s.lens_u * (1 << a))), int(std::floor(s.lens_v * (1 << (k - a))))});
        }
        EXPECT_EQ(cells.size(), size_t(n)) << "pixel " << x << ", " << n << " samples, grid 2^" << a;
      }
    }
  }
  EXPECT_NE(SampleSequence(90, 0, 17).Get(0).lens_u, SampleSequence(90, 1, 17).Get(0).lens_u);
  EXPECT_EQ(SampleSequence(90, 5, 17).Get(3).lens_v, SampleSequence(90, 5, 17).Get(3).lens_v);
}

// Each bit of a scrambled value depends only on the bits above it: the top 8 bits of 0 .. 255 (as fractions)
// come out as a permutation of 0 .. 255.
TEST(SampleSequence, OwenScrambleIsAPermutationOfDyadicIntervals) {
  for (uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
    std::set<uint32_t> top;
    for (uint32_t v = 0; v < 256; ++v) top.insert(OwenScramble(v << 24, seed) >> 24);
    EXPECT_EQ(top.size(), 256u) << seed;
  }
}

// Sobol's second dimension, against its definition bit by bit (direction numbers v_1 = 2^31,
// v_k = v_(k-1) xor v_(k-1) >> 1): its first points, every 16-bit index, and full 32-bit ones (the
// shuffled indices the lens uses).
TEST(SampleSequence, Sobol2MatchesItsDirectionNumbers) {
  auto by_bits = [](uint32_t index) {
    uint32_t result = 0;
    for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1) {
      if (index & 1) result ^= v;
    }
    return result * (1.0 / 4294967296.0);
  };
  const double first[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) EXPECT_EQ(Sobol2(i), first[i]) << i;
  for (uint32_t i = 0; i < (1u << 16); ++i) ASSERT_EQ(Sobol2(i), by_bits(i)) << i;
  uint32_t state = 99;
  for (int n = 0; n < 100000; ++n) {
    state = state * 1664525u + 1013904223u;
    ASSERT_EQ(Sobol2(state), by_bits(state)) << state;
  }
  EXPECT_EQ(Sobol2(0xffffffffu), by_bits(0xffffffffu));
}

// GetPixel is Get's pixel offsets, to the bit, with the lens and time at their centres.
TEST(SampleSequence, GetPixelIsGetsPixelOffsets) {
  for (uint32_t x : {0u, 7u, 639u}) {
    const SampleSequence sequence(42, x, 3 * x + 1);
    for (uint32_t index = 0; index < 64; ++index) {
      const PixelSample all = sequence.Get(index), pixel = sequence.GetPixel(index);
      EXPECT_EQ(all.pixel_x, pixel.pixel_x);
      EXPECT_EQ(all.pixel_y, pixel.pixel_y);
      EXPECT_EQ(pixel.lens_u, 0.5);
      EXPECT_EQ(pixel.lens_v, 0.5);
      EXPECT_EQ(pixel.time, 0.5);
    }
  }
}

}  // namespace
}  // namespace cinepath::preview
