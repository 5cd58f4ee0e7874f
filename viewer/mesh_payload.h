// The scene mesh as the page carries it: positions in three.js's frame (core/three_frame.h)
// quantized to 16 bits per axis over the mesh's bounds (a 500 m scene keeps 8 mm steps), vertex colours
// as 8-bit sRGB, texture coordinates (TEXCOORD_0, when the mesh has a base-colour texture) quantized to
// 16 bits over [0, 1], triangle indices as 16- or 32-bit integers. Each of the three streams is delta-coded
// (each value minus the one `stride` before it, modulo 2^bits: stride 3 for positions and colours, so x
// follows x, 2 for texture coordinates, 1 for indices) and split into byte planes (every value's low byte, then every
// second byte, ...), then the three, one after the other, are zlib-deflated (viewer/deflate.h): neighbouring vertices
// and indices differ by little, so the planes of high bytes are nearly constant and deflate to almost nothing. The page
// inflates it with the browser's DecompressionStream, sums the deltas back and builds one indexed BufferGeometry: no
// glTF or Draco decoder in the page (docs/view.md, "Size").
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene_mesh.h"

namespace cinepath::viewer {

struct MeshPayload {
  size_t num_vertices = 0;
  size_t num_triangles = 0;
  bool has_colors = false;              // false: the page shades a neutral grey with a light
  bool has_texcoords = false;           // with a texture: the page maps it (times the vertex colours)
  std::string texture_mime_type;        // the base-colour image of the first textured material, as stored
  std::vector<uint8_t> texture;         // in the GLB (JPEG or PNG bytes); empty = none
  int index_bytes = 2;                  // 2 when every index fits in 16 bits, else 4
  std::array<double, 3> min_three_m{};  // bounds in three.js's frame: the quantization range
  std::array<double, 3> max_three_m{};
  // positions (2 planes), colours (1 plane, when has_colors), texture coordinates (2 planes, when
  // has_texcoords), indices (index_bytes planes)
  std::string deflated;
  size_t inflated_bytes = 0;
};

MeshPayload EncodeMeshPayload(const scene::SceneMesh& mesh);

// `values` (each < 2^(8 width)) delta-coded at `stride` modulo 2^(8 width), as `width` byte planes.
std::string DeltaBytePlanes(const std::vector<uint32_t>& values, int width, int stride);

// Linear [0, 1] -> 8-bit sRGB (the transfer function, rounded).
uint8_t LinearToSrgb8(float linear);

}  // namespace cinepath::viewer
