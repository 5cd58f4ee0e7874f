// The texture atlas layout: charts of connected faces that take their colour from the same photo, each
// kept as that photo shows it (the chart's texture coordinates are its faces' projections in the photo,
// scaled), packed into one square image with stb_rect_pack (skyline, best fit, tallest first) and
// surrounded by `padding_px` texels that the baker fills by dilation, so that bilinear filtering and
// the first mipmap levels do not bleed one chart into its neighbour.
//
// One scale serves every chart (texels per photo pixel, at most `max_texels_per_pixel`, i.e. never
// finer than the photos): the largest that packs, found by starting from the area estimate and
// shrinking by 7 % until every chart fits. Faces no photo sees share one small chart that the baker
// leaves white: their colour is COLOR_0 (glTF multiplies the two, texture_bake.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "photogrammetry/mesh/triangle_mesh.h"
#include "photogrammetry/texture/texture_view.h"

namespace cinepath::photogrammetry {

struct TextureAtlasOptions {
  int size_px = 4096;  // the atlas is size_px x size_px
  int padding_px = 2;
  double max_texels_per_pixel = 1.0;
};

struct TextureChart {
  int view = -1;                   // the photo; -1 = the chart of faces no photo sees
  std::vector<uint32_t> faces;     // in index order
  Eigen::AlignedBox2d box_px;      // the faces' projections in the photo
  int x = 0, y = 0, w = 0, h = 0;  // packed rectangle in atlas texels, padding included
};

struct TextureAtlas {
  int size_px = 0;
  int padding_px = 0;
  double texels_per_pixel = 0;       // the scale every chart shares
  std::vector<TextureChart> charts;  // photo charts in order of their first face, then the unseen one
  std::vector<int> face_chart;       // per face
  // Per face, its corners in atlas texels (continuous: the upper-left texel's centre is (0.5, 0.5)).
  std::vector<std::array<Eigen::Vector2f, 3>> corner_texel;
  int pack_attempts = 0;
};

// `label` per face (texture_view_selection.h), -1 for none. RuntimeError when the charts do not fit
// even at a tiny scale (more charts than texels).
TextureAtlas BuildTextureAtlas(const TriangleMesh& mesh, const std::vector<TextureView>& views,
                               const std::vector<int>& label, const TextureAtlasOptions& options = {});

}  // namespace cinepath::photogrammetry
