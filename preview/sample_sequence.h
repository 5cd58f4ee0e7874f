// Low-discrepancy samples for the pixel, lens and time dimensions, randomized per pixel from a hash of
// (frame, x, y). A pixel's samples depend on nothing else, so an image is the same at any thread count and
// in any shard.
//   lens    the first two dimensions of Sobol' (a (0,2)-sequence: every power-of-two prefix is
//           stratified in both axes), Owen-scrambled (nested uniform scrambling by Laine and Karras's hash,
//           as Burley 2020 and Cycles' Sobol-Burley do: the stratification kept, the points' regular
//           structure not), the index shuffled the same way, mapped onto the disk by ConcentricDisk
//   pixel and time: a toroidal shift (Cranley-Patterson rotation) of
//   pixel   Halton bases 3 and 5 (the box filter of 1 px)
//   time    Halton base 7 (the shutter interval)
#pragma once

#include <cstdint>

namespace cinepath::preview {

struct PixelSample {
  double pixel_x = 0.5, pixel_y = 0.5;  // within the pixel, [0, 1)
  double lens_u = 0.5, lens_v = 0.5;    // [0, 1)^2, before the disk map
  double time = 0.5;                    // [0, 1) across the shutter interval
};

class SampleSequence {
 public:
  SampleSequence(uint64_t frame, uint32_t x, uint32_t y);
  PixelSample Get(uint32_t index) const;
  // Only the pixel offsets of Get(index) (the lens and the time left at their centres): what a ray
  // without lens or shutter needs (draft's edge rays), without the lens's scrambles.
  PixelSample GetPixel(uint32_t index) const;

 private:
  double shift_[5];         // [2..4]: pixel x, pixel y, time
  uint32_t lens_seeds_[3];  // the index's shuffle, lens u, lens v
};

// Radical inverse of `index` in `base` (van der Corput for base 2).
double RadicalInverse(uint32_t index, uint32_t base);
// The second dimension of Sobol' (direction numbers v_k = 2^(31-k) xor v_(k-1) >> 1).
double Sobol2(uint32_t index);
// A nested uniform (Owen) scramble of a 32-bit fraction: bit k flips by a hash of the bits above it and
// the seed, so every dyadic interval maps onto one of the same size.
uint32_t OwenScramble(uint32_t bits, uint32_t seed);

}  // namespace cinepath::preview
