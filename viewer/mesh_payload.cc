#include "viewer/mesh_payload.h"

#include <algorithm>
#include <cmath>

#include "core/three_frame.h"
#include "viewer/deflate.h"

namespace cinepath::viewer {
std::string DeltaBytePlanes(const std::vector<uint32_t>& values, int width, int stride) {
  const uint64_t modulus = uint64_t(1) << (8 * width);
  std::vector<uint32_t> deltas(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    const uint64_t previous = i >= size_t(stride) ? values[i - stride] : 0;
    deltas[i] = uint32_t((uint64_t(values[i]) + modulus - previous) % modulus);
  }
  std::string planes;
  planes.reserve(values.size() * width);
  for (int b = 0; b < width; ++b) {
    for (uint32_t d : deltas) planes.push_back(char(d >> (8 * b) & 0xff));
  }
  return planes;
}

uint8_t LinearToSrgb8(float linear) {
  const float x = std::clamp(linear, 0.0f, 1.0f);
  const float srgb = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(srgb * 255.0f));
}

MeshPayload EncodeMeshPayload(const scene::SceneMesh& mesh) {
  MeshPayload payload;
  payload.num_vertices = mesh.num_vertices();
  payload.num_triangles = mesh.num_faces();
  payload.has_colors = mesh.has_colors();
  // The texture of the first material that has one (cinepath mesh writes one material).
  for (const auto& material : mesh.materials) {
    if (material.base_color_image >= 0 && size_t(material.base_color_image) < mesh.images.size() &&
        mesh.has_texcoords()) {
      const auto& image = mesh.images[size_t(material.base_color_image)];
      payload.has_texcoords = true;
      payload.texture_mime_type = image.mime_type;
      payload.texture = image.encoded;
      break;
    }
  }
  payload.index_bytes = mesh.num_vertices() <= 65536 ? 2 : 4;
  Eigen::AlignedBox3d box;
  for (const auto& p : mesh.positions_enu_m) box.extend(ThreeFromEnu(p));
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());
  for (int a = 0; a < 3; ++a) {
    payload.min_three_m[a] = box.min()[a];
    payload.max_three_m[a] = box.max()[a];
  }
  std::vector<uint32_t> quantized;
  quantized.reserve(3 * mesh.num_vertices());
  for (const auto& p : mesh.positions_enu_m) {
    const Eigen::Vector3d q = ThreeFromEnu(p);
    for (int a = 0; a < 3; ++a) {
      const double extent = box.max()[a] - box.min()[a];
      const double unit = extent > 0 ? (q[a] - box.min()[a]) / extent : 0.0;
      quantized.push_back(uint32_t(std::lround(std::clamp(unit, 0.0, 1.0) * 65535.0)));
    }
  }
  std::string raw = DeltaBytePlanes(quantized, 2, 3);
  if (payload.has_colors) {
    std::vector<uint32_t> colors;
    colors.reserve(3 * mesh.num_vertices());
    for (const auto& c : mesh.colors_linear) {
      for (int a = 0; a < 3; ++a) colors.push_back(LinearToSrgb8(c[a]));
    }
    raw += DeltaBytePlanes(colors, 1, 3);
  }
  if (payload.has_texcoords) {
    std::vector<uint32_t> uv;
    uv.reserve(2 * mesh.num_vertices());
    for (const auto& t : mesh.texcoords) {
      for (int a = 0; a < 2; ++a) uv.push_back(uint32_t(std::lround(std::clamp(double(t[a]), 0.0, 1.0) * 65535.0)));
    }
    raw += DeltaBytePlanes(uv, 2, 2);
  }
  std::vector<uint32_t> indices;
  indices.reserve(3 * mesh.num_faces());
  for (const auto& face : mesh.faces) indices.insert(indices.end(), face.begin(), face.end());
  raw += DeltaBytePlanes(indices, payload.index_bytes, 1);
  payload.inflated_bytes = raw.size();
  payload.deflated = DeflateZlib(raw);
  return payload;
}

}  // namespace cinepath::viewer
