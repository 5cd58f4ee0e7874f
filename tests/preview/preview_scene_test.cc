// The texture rows a frame can read (TextureRowsSampled), which DecodeTextures alone decodes.
#include "preview/preview_scene.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace cinepath::preview {
namespace {

// One triangle per entry of `vs` (the three vertices' v; u spread over [0.1, 0.9]), each with material
// `material[i]`; material 0 takes image 0, material 1 image 1.
scene::SceneMesh UvMesh(const std::vector<std::array<float, 3>>& vs, const std::vector<int>& material) {
  scene::SceneMesh mesh;
  for (size_t i = 0; i < vs.size(); ++i) {
    const uint32_t base = uint32_t(mesh.positions_enu_m.size());
    for (int k = 0; k < 3; ++k) {
      mesh.positions_enu_m.emplace_back(double(i) + k, double(k % 2), 0.0);
      mesh.texcoords.emplace_back(0.1f + 0.4f * float(k), vs[i][size_t(k)]);
    }
    mesh.faces.push_back({base, base + 1, base + 2});
    mesh.face_material.push_back(material[i]);
  }
  mesh.materials.resize(2);
  mesh.materials[0].base_color_image = 0;
  mesh.materials[1].base_color_image = 1;
  mesh.images.resize(2);
  return mesh;
}

std::vector<int> Flagged(const std::vector<uint8_t>& rows) {
  std::vector<int> out;
  for (size_t r = 0; r < rows.size(); ++r)
    if (rows[r]) out.push_back(int(r));
  return out;
}

std::vector<int> Range(int begin, int end) {
  std::vector<int> out;
  for (int r = begin; r < end; ++r) out.push_back(r);
  return out;
}

TEST(TextureRows, AFacesVRangeItsBilinearNeighbourAndTwoRowsMargin) {
  // v from 0.25 to 0.5 on 100 rows: Sample reads rows floor(25 - 0.5) = 24 to floor(50 - 0.5) + 1 = 50.
  const scene::SceneMesh mesh = UvMesh({{0.25f, 0.5f, 0.3f}, {0.8f, 0.9f, 0.85f}}, {0, 1});
  EXPECT_EQ(Flagged(TextureRowsSampled(mesh, 0, 100)), Range(22, 53));
  EXPECT_EQ(Flagged(TextureRowsSampled(mesh, 1, 100)), Range(77, 93));  // floor(79.5) - 2 to floor(89.5) + 3
}

TEST(TextureRows, RowsWrapAsTheSamplerDoes) {
  // v down to 0.001: Sample's row floor(0.1 - 0.5) = -1 is the last row (REPEAT).
  const scene::SceneMesh mesh = UvMesh({{0.001f, 0.1f, 0.05f}}, {0});
  std::vector<int> expected = Range(0, 13);
  for (int r : Range(97, 100)) expected.push_back(r);
  EXPECT_EQ(Flagged(TextureRowsSampled(mesh, 0, 100)), expected);
}

TEST(TextureRows, NoTexcoordsNoRowsAndBadOnesEveryRow) {
  scene::SceneMesh mesh = UvMesh({{0.25f, 0.5f, 0.3f}}, {0});
  EXPECT_EQ(Flagged(TextureRowsSampled(mesh, 1, 100)), std::vector<int>{});  // no face takes image 1
  mesh.texcoords[1].y() = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(Flagged(TextureRowsSampled(mesh, 0, 100)), Range(0, 100));
  mesh.texcoords[1].y() = 3.0f;  // spans the texture more than once
  EXPECT_EQ(Flagged(TextureRowsSampled(mesh, 0, 100)), Range(0, 100));
  mesh.texcoords.clear();
  EXPECT_EQ(Flagged(TextureRowsSampled(mesh, 0, 100)), std::vector<int>{});
}

// Vertices whose v spans the texture: every row, without looking at the faces (so a mesh mapped over its
// whole texture costs a pass over its vertices), though these two faces leave a gap between them.
TEST(TextureRows, VerticesSpanningTheTextureTakeEveryRow) {
  const scene::SceneMesh mesh = UvMesh({{0.01f, 0.02f, 0.03f}, {0.97f, 0.98f, 0.99f}}, {0, 0});
  EXPECT_EQ(Flagged(TextureRowsSampled(mesh, 0, 100)), Range(0, 100));
  const scene::SceneMesh apart = UvMesh({{0.1f, 0.12f, 0.13f}, {0.8f, 0.82f, 0.83f}}, {0, 0});
  EXPECT_EQ(Flagged(TextureRowsSampled(apart, 0, 100)).size(), size_t(9 + 9));  // rows 7-15 and 77-85
}

// The rows left out are never read: every lookup inside the faces (their corners and edges included, and
// the wrap past v = 0) is the same from a texture whose rows left out hold other bytes.
TEST(TextureRows, LookupsInsideTheFacesNeverReadARowLeftOut) {
  const scene::SceneMesh mesh =
      UvMesh({{0.25f, 0.5f, 0.3f}, {0.002f, 0.03f, 0.01f}, {0.6f, 0.6f, 0.61f}, {0.4f, 0.41f, 0.45f}}, {0, 0, 0, 0});
  constexpr int kSize = 64;
  const std::vector<uint8_t> rows = TextureRowsSampled(mesh, 0, kSize);
  ASSERT_LT(Flagged(rows).size(), size_t(kSize));
  Texture full, partial;
  full.width = partial.width = full.height = partial.height = kSize;
  full.srgb.resize(size_t(kSize) * kSize * 3);
  partial.srgb.resize(full.srgb.size());
  for (size_t i = 0; i < full.srgb.size(); ++i) {
    full.srgb[i] = uint8_t(i * 37 % 251);
    partial.srgb[i] = rows[i / 3 / kSize] ? full.srgb[i] : 255 - full.srgb[i];
  }
  std::mt19937 random(5);
  std::uniform_real_distribution<float> unit(0, 1);
  for (const auto& f : mesh.faces) {
    for (int n = 0; n < 2000; ++n) {
      float u = n < 3 ? float(n == 1) : unit(random), v = n < 3 ? float(n == 2) : unit(random);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      const Eigen::Vector2f uv =
          (1 - u - v) * mesh.texcoords[f[0]] + u * mesh.texcoords[f[1]] + v * mesh.texcoords[f[2]];
      ASSERT_EQ(full.Sample(uv), partial.Sample(uv)) << uv.transpose();
    }
  }
}

}  // namespace
}  // namespace cinepath::preview
