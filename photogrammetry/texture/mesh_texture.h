// `cinepath mesh --images`: the mesh textured from the registered photos (docs/mesh.md, "Texture").
//
//   views ─► view selection (visibility by ray casts, quality, seam smoothing; texture_view_selection.h)
//         ─► exposure gains on the overlaps (exposure_gain.h)
//         ─► charts packed into an atlas (texture_atlas.h) ─► baked from the photos (texture_bake.h)
//         ─► vertices split per chart with their texture coordinates, the atlas encoded (JPEG or PNG)
//
// The output mesh has the input's faces in the same order; its vertices are split where charts meet.
// Its colours (COLOR_0 in the GLB) are white on faces a photo textures and the input's vertex colours on
// faces no photo sees, whose texels are white: glTF multiplies COLOR_0 by the base-colour texture (glTF
// 2.0, "Meshes": COLOR_0 multiplies the base colour), so every viewer shows each face in exactly one of
// the two. Deterministic: the same bytes at any thread count.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/json.h"
#include "photogrammetry/io/colmap_model.h"
#include "photogrammetry/io/photo_image.h"
#include "photogrammetry/mesh/triangle_mesh.h"
#include "photogrammetry/pipeline/surface_pipeline.h"
#include "photogrammetry/texture/exposure_gain.h"
#include "photogrammetry/texture/texture_atlas.h"
#include "photogrammetry/texture/texture_view.h"
#include "photogrammetry/texture/texture_view_selection.h"

namespace cinepath::photogrammetry {

enum class TextureFormat { kJpeg, kPng };

// The atlas size of each --quality preset: draft 2048, standard 4096, final 8192 texels square.
int DefaultTexturePx(Quality quality);

struct MeshTextureOptions {
  int texture_px = 4096;  // --texture-px; the atlas is square
  TextureFormat format = TextureFormat::kJpeg;
  int jpeg_quality = 90;
  int padding_px = 2;
  bool level_exposure = true;
  ViewSelectionOptions selection;
  ExposureGainOptions exposure;
  std::vector<std::string> excluded_images;  // --texture-exclude: photos never used (e.g. held out)
  bool report_times = true;

  void Check() const;  // InputError naming the option
};

struct TexturedMesh {
  TriangleMesh mesh;                       // split per chart; colours as above
  std::vector<Eigen::Vector2f> texcoords;  // per vertex, glTF convention (u right, v down, [0, 1])
  RgbImage atlas;
  std::string image_bytes;  // the atlas encoded
  std::string mime_type;    // "image/jpeg" or "image/png"
  Json report;              // scene.json "texture"
};

// Textures `mesh` from `views` with `photos[v]` the pixels of views[v] (same size as its camera).
TexturedMesh TextureMesh(const TriangleMesh& mesh, const std::vector<TextureView>& views,
                         const std::vector<RgbImage>& photos, const MeshTextureOptions& options);

// The views of every registered image of `model_enu` (in image-id order) whose photo is in
// `images_dir` and not excluded, read through OpenImageIO, then TextureMesh. Photos that are missing
// are reported (report "photos_missing"); a photo whose size differs from its camera's is an InputError
// naming it. Appends the photos read to `inputs`.
TexturedMesh TextureMeshFromPhotos(const TriangleMesh& mesh, const ColmapModel& model_enu,
                                   const std::string& images_dir, const MeshTextureOptions& options,
                                   std::vector<std::string>* inputs);

}  // namespace cinepath::photogrammetry
