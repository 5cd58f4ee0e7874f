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

double Sobol2(uint32_t index) {
  uint32_t result = 0;
  for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1) {
    if (index & 1) result ^= v;
  }
  return result * (1.0 / 4294967296.0);
}

SampleSequence::SampleSequence(uint64_t frame, uint32_t x, uint32_t y) {
  uint64_t state = Mix(frame * 0x100000001b3ULL ^ (uint64_t(x) << 32 | y));
  for (double& shift : shift_) {
    state = Mix(state);
    shift = (state >> 11) * (1.0 / 9007199254740992.0);
  }
}

PixelSample SampleSequence::Get(uint32_t index) const {
  PixelSample s;
  s.lens_u = Wrap(RadicalInverse(index, 2) + shift_[0]);
  s.lens_v = Wrap(Sobol2(index) + shift_[1]);
  s.pixel_x = Wrap(RadicalInverse(index, 3) + shift_[2]);
  s.pixel_y = Wrap(RadicalInverse(index, 5) + shift_[3]);
  s.time = Wrap(RadicalInverse(index, 7) + shift_[4]);
  return s;
}

}  // namespace cinepath::preview
