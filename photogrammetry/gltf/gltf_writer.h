// scene.glb: a TriangleMesh in local ENU metres → binary glTF 2.0 bytes.
//
// Frames (docs/design.md): ENU (e, n, u) is stored as glTF (e, u, −n), so glTF +Y is up and every
// viewer shows the scene upright. Positions float32 (ENU keeps them near the origin), indices
// uint32, vertex colours as COLOR_0 (float VEC3, linear: the sRGB point colours are converted with the
// sRGB transfer function, as glTF defines COLOR_0 to be linear).
// With a texture (GlbTexture), the primitive also carries TEXCOORD_0 (float VEC2) and the material a
// baseColorTexture: the image (JPEG or PNG bytes) in a bufferView of the binary chunk, a linear,
// mipmapped, clamp-to-edge sampler. glTF multiplies the texture by COLOR_0 (mesh_texture.h says how the
// two are arranged so that each face shows one).
// With draco on, the primitive carries KHR_draco_mesh_compression (encoded here with the Draco
// library; tinygltf cannot write Draco) and the accessors hold counts and bounds only.
// The bytes are deterministic: the same mesh and options give the same GLB.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/json.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct GlbWriteOptions {
  bool draco = false;
  int draco_position_bits = 16;  // 500 m / 2^16 ≈ 7.6 mm (a 500 m scene quantized to 16 bits)
  int draco_color_bits = 10;
  int draco_texcoord_bits = 16;     // 1/65536 of the atlas: a quarter texel at 16384 texels
  int draco_compression_level = 7;  // Draco speed = 10 − level
  Json extras;                      // copied into asset.extras and scene.extras (object or null)
};

// Linear value of an 8-bit sRGB channel (IEC 61966-2-1).
float LinearFromSrgb8(uint8_t value);

struct GlbTexture {
  std::vector<Eigen::Vector2f> texcoords;  // one per vertex (glTF: u right, v down, [0, 1] over the image)
  std::string image_bytes;                 // encoded
  std::string mime_type;                   // "image/jpeg" or "image/png"
};

// Throws InputError for an empty mesh or an index out of range, RuntimeError if Draco fails.
std::string WriteGlb(const TriangleMesh& mesh_enu, const GlbWriteOptions& options);
// The same with a base-colour texture; InputError when the texture coordinates are not one per vertex
// or the image is empty.
std::string WriteGlb(const TriangleMesh& mesh_enu, const GlbTexture* texture, const GlbWriteOptions& options);

}  // namespace cinepath::photogrammetry
