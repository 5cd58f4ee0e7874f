#include "preview/sample_sequence.h"

#include <cmath>

namespace cinepath::preview {
namespace {

// SplitMix64 finaliser: a well-mixed 64-bit hash.
uint64_t Mix(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double Wrap(double value) { return value - std::floor(value); }

uint32_t ReverseBits(uint32_t v) {
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
  return __builtin_bswap32(v);  // the bytes' order, in one instruction
}

// OwenScramble of the value whose bit-reversal is `reversed`: the hash works on reversed bits, so a
// caller that holds them saves two reversals.
uint32_t OwenScrambleReversed(uint32_t reversed, uint32_t seed) {
  uint32_t x = reversed + seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return ReverseBits(x);
}

// The second Sobol' dimension is linear over GF(2): the xor of the direction numbers of the index's set
// bits. Four tables hold that xor for every value of each of the index's bytes, so an index costs four
// lookups instead of one step per bit (the shuffled indices use all 32 bits).
class Sobol2Table {
 public:
  // `reversed`: each value's bits reversed (the direction numbers reversed: reversal is linear over xor).
  explicit Sobol2Table(bool reversed) {
    uint32_t direction[32];
    uint32_t v = 1u << 31;
    for (int k = 0; k < 32; ++k, v ^= v >> 1) direction[k] = reversed ? ReverseBits(v) : v;
    for (int byte = 0; byte < 4; ++byte) {
      for (uint32_t value = 0; value < 256; ++value) {
        uint32_t result = 0;
        for (int bit = 0; bit < 8; ++bit) {
          if (value >> bit & 1) result ^= direction[8 * byte + bit];
        }
        table_[byte][value] = result;
      }
    }
  }
  uint32_t operator()(uint32_t index) const {
    return table_[0][index & 0xff] ^ table_[1][index >> 8 & 0xff] ^ table_[2][index >> 16 & 0xff] ^
           table_[3][index >> 24];
  }

 private:
  uint32_t table_[4][256];
};

uint32_t Sobol2Bits(uint32_t index) {
  static const Sobol2Table table(false);
  return table(index);
}

uint32_t Sobol2ReversedBits(uint32_t index) {
  static const Sobol2Table table(true);
  return table(index);
}

constexpr double kTwoTo32 = 4294967296.0;

}  // namespace

double RadicalInverse(uint32_t index, uint32_t base) {
  double result = 0, scale = 1.0 / base;
  while (index > 0) {
    result += (index % base) * scale;
    index /= base;
    scale /= base;
  }
  return result;
}

double Sobol2(uint32_t index) { return Sobol2Bits(index) * (1.0 / kTwoTo32); }

uint32_t OwenScramble(uint32_t bits, uint32_t seed) {
  // Laine and Karras's hash on the reversed bits (Burley 2020, "Practical Hash-based Owen Scrambling"):
  // each bit flips depending only on the bits above it, with a seed.
  return OwenScrambleReversed(ReverseBits(bits), seed);
}

SampleSequence::SampleSequence(uint64_t frame, uint32_t x, uint32_t y) {
  uint64_t state = Mix(frame * 0x100000001b3ULL ^ (uint64_t(x) << 32 | y));
  for (double& shift : shift_) {
    state = Mix(state);
    shift = (state >> 11) * (1.0 / 9007199254740992.0);
  }
  for (uint32_t& seed : lens_seeds_) {
    state = Mix(state);
    seed = uint32_t(state >> 32);
  }
}

PixelSample SampleSequence::Get(uint32_t index) const {
  PixelSample s;
  // The lens: the index shuffled (an Owen scramble keeps every power-of-two prefix a prefix), then both
  // dimensions Owen-scrambled with the pixel's seeds.
  // u is Sobol's first dimension, the reversed index, which the scramble wants reversed again: the index
  // itself. v's table holds the reversed values (a reversal is linear over xor as Sobol' is).
  const uint32_t i = OwenScramble(index, lens_seeds_[0]);
  s.lens_u = OwenScrambleReversed(i, lens_seeds_[1]) * (1.0 / kTwoTo32);
  s.lens_v = OwenScrambleReversed(Sobol2ReversedBits(i), lens_seeds_[2]) * (1.0 / kTwoTo32);
  s.pixel_x = Wrap(RadicalInverse(index, 3) + shift_[2]);
  s.pixel_y = Wrap(RadicalInverse(index, 5) + shift_[3]);
  s.time = Wrap(RadicalInverse(index, 7) + shift_[4]);
  return s;
}

PixelSample SampleSequence::GetPixel(uint32_t index) const {
  PixelSample s;
  s.pixel_x = Wrap(RadicalInverse(index, 3) + shift_[2]);
  s.pixel_y = Wrap(RadicalInverse(index, 5) + shift_[3]);
  return s;
}

}  // namespace cinepath::preview
