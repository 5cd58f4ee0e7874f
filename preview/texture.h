// The mesh's base-colour textures as render reads them: 8-bit sRGB texels, sampled bilinearly in linear
// light, and for draft a pyramid of coarser levels, each texel the mean (in linear light) of four of the
// level above, so that a pixel whose footprint covers many texels reads their mean from one level instead
// of one texel from the whole atlas (docs/render.md, "Texture levels").
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include <Eigen/Core>

#include "preview/image_files.h"
#include "scene/scene_mesh.h"

namespace cinepath::preview {

// One level of a texture: rows from the top (glTF uv: u right, v down), 3 bytes a texel. The texels stay
// 8-bit sRGB, as the image holds them (50 MB for a 4096² atlas, where linear floats took 201 MB and a
// quarter of a second of pow() at load); each lookup turns its four texels into linear light through a
// 256-entry table, then interpolates, as renderers do with sRGB textures. The same linear values as
// decoding to floats first, so the same frames.
struct TextureLevel {
  int width = 0;
  int height = 0;
  ImageBytes srgb;                                          // width x height x RGB
  Eigen::Vector3f Sample(const Eigen::Vector2f& uv) const;  // bilinear in linear light, wrapping (glTF REPEAT)
};

// A decoded base-colour texture (level 0, the image itself) and its coarser levels, when built: level k
// is coarser[k - 1], max(1, width / 2^k) x max(1, height / 2^k), texel (i, j) the linear mean of texels
// (2i .. 2i+1, 2j .. 2j+1) of level k - 1, rounded to 8-bit sRGB. Only the rows a face's lookup can read
// hold texels (TextureLevelRowsSampled): the rest of an atlas is never decoded nor averaged.
struct Texture : TextureLevel {
  std::vector<TextureLevel> coarser;
  int levels() const { return 1 + int(coarser.size()); }
  // Bilinear at `level` (0: the image; past the coarsest: the coarsest).
  Eigen::Vector3f SampleLevel(const Eigen::Vector2f& uv, int level) const {
    if (level <= 0 || coarser.empty()) return Sample(uv);
    return coarser[size_t(std::min(level, int(coarser.size())) - 1)].Sample(uv);
  }
};

// The rows of the mesh's image `image` (`height` rows) that a lookup can read: every row that
// TextureLevel::Sample's bilinear taps can reach from a uv inside a face whose material takes that image as its
// base colour (the face's v range, the neighbour row, two rows' margin for rounding, wrapped as REPEAT
// wraps). The rest of a texture is never read: no face maps onto it (a texture atlas's unused space).
std::vector<uint8_t> TextureRowsSampled(const scene::SceneMesh& mesh, size_t image, int height);

// The same for a pyramid of `levels` levels whose level 0 has `height` rows: element k holds the rows of
// level k a lookup at that level can read, and every row of level k that a wanted row of level k + 1 is
// averaged from (so level 0's are the rows to decode).
std::vector<std::vector<uint8_t>> TextureLevelRowsSampled(const scene::SceneMesh& mesh, size_t image, int height,
                                                          int levels);

// The number of levels a pyramid of a width x height image has down to one texel along its shorter side,
// at most `max_levels`.
int PyramidLevels(int width, int height, int max_levels);

// Builds texture's coarser levels (levels() becomes `rows.size()`) from its level 0: `rows` as
// TextureLevelRowsSampled gives them, and level 0 holds at least rows[0]'s rows. Rows in parallel (TBB),
// the same bytes at any thread count.
void BuildCoarserLevels(Texture* texture, const std::vector<std::vector<uint8_t>>& rows);

// The mesh's images decoded, one texture each (libjpeg, libpng), with `max_levels` levels (1: the
// image alone; more: the coarser levels built too, for draft). InputError for an image that cannot be.
// A JPEG's rows no lookup can read (TextureRowsSampled, or the pyramid's TextureLevelRowsSampled) are left
// unwritten, and after the last row that can be read nothing is decoded: the bundled 4096² atlas's charts
// fill its top 30 % of rows.
std::vector<Texture> DecodeTextures(const scene::SceneMesh& mesh, int max_levels = 1);

// The level whose texel is nearest a footprint of t texels (of level 0) a side, given t²: log2 t rounded,
// so from √2 texels up level 1, from 2√2 level 2, and so on; below √2 (or a NaN), level 0. (The binary
// exponent of 2 t², halved: round(log2 t) = floor(log2(√2 t)) = floor(log2(2 t²) / 2), no logarithm.)
inline int LevelOfFootprint(double texels_squared) {
  if (!(texels_squared >= 2)) return 0;
  const double x = 2 * texels_squared;
  uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return (int((bits >> 52) & 0x7ff) - 1023) >> 1;
}

// Per face: texels of level 0 per metre of the surface (the square root of the face's texture area in
// texels over its area in square metres), 0 for a face without a base-colour texture or without area.
// A lookup's level is log2 of its footprint in texels (PreviewScene::SurfaceColor).
std::vector<float> FaceTexelsPerMetre(const scene::SceneMesh& mesh, const std::vector<Texture>& textures);

}  // namespace cinepath::preview
