// Bakes the atlas (texture_atlas.h): every texel of a chart whose centre lies in one of its faces (in
// atlas space) takes the colour of the scene point it stands for, projected into the chart's photo
// through the full camera model (distortion included) and sampled bilinearly in linear light, times the
// photo's exposure gain (exposure_gain.h), stored as 8-bit sRGB. Texels of the chart's rectangle that no
// face covers take the mean of their covered neighbours, ring after ring (the padding: no bleeding
// under bilinear filtering and the first mipmaps). The chart of faces no photo sees is white: their
// colour is the mesh's COLOR_0, which glTF multiplies with the texture. Texels outside every chart are
// mid grey.
//
// Each chart writes only its own rectangle, so charts bake in parallel and the bytes do not depend on
// the thread count.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "photogrammetry/io/photo_image.h"
#include "photogrammetry/mesh/triangle_mesh.h"
#include "photogrammetry/texture/texture_atlas.h"
#include "photogrammetry/texture/texture_view.h"

namespace cinepath::photogrammetry {

struct BakeStats {
  int64_t texels_covered = 0;  // texel centres inside a face of a photo chart
  int64_t texels_padding = 0;  // filled by dilation
};

// `photos[v]` is the image of `views[v]` (may be null for views no chart uses); `gains[v]` its
// per-channel gain (empty: 1).
RgbImage BakeTextureAtlas(const TriangleMesh& mesh, const std::vector<TextureView>& views,
                          const std::vector<const RgbImage*>& photos, const std::vector<Eigen::Vector3f>& gains,
                          const TextureAtlas& atlas, BakeStats* stats = nullptr);

}  // namespace cinepath::photogrammetry
