// The texture rows a frame can read (TextureRowsSampled), which DecodeTextures alone decodes, and the
// coarser levels draft reads: each texel the linear mean of four, built from those rows alone.
#include "preview/texture.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "preview/image_files.h"

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
// `per_face` uvs inside each face of `mesh`: its three corners, then uniform random points.
std::vector<Eigen::Vector2f> UvsInsideFaces(const scene::SceneMesh& mesh, int per_face, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> unit(0, 1);
  std::vector<Eigen::Vector2f> uvs;
  for (const auto& f : mesh.faces) {
    for (int n = 0; n < per_face; ++n) {
      float u = n < 3 ? float(n == 1) : unit(random), v = n < 3 ? float(n == 2) : unit(random);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      uvs.push_back((1 - u - v) * mesh.texcoords[f[0]] + u * mesh.texcoords[f[1]] + v * mesh.texcoords[f[2]]);
    }
  }
  return uvs;
}

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
  for (const Eigen::Vector2f& uv : UvsInsideFaces(mesh, 2000, 5))
    ASSERT_EQ(full.Sample(uv), partial.Sample(uv)) << uv.transpose();
}

// A texture of `size` x `size` texels, every byte a hash of its index (`flip`: every byte inverted).
Texture HashTexture(int size, bool flip = false) {
  Texture texture;
  texture.width = texture.height = size;
  texture.srgb.resize(size_t(size) * size * 3);
  for (size_t i = 0; i < texture.srgb.size(); ++i) {
    const uint8_t v = uint8_t(i * 37 % 251);
    texture.srgb[i] = flip ? uint8_t(255 - v) : v;
  }
  return texture;
}

std::vector<std::vector<uint8_t>> EveryRow(int height, int levels) {
  std::vector<std::vector<uint8_t>> rows;
  for (int k = 0; k < levels; ++k, height = std::max(1, height / 2)) rows.emplace_back(size_t(height), 1);
  return rows;
}

float Linear(uint8_t v) {
  const float c = float(v) * (1.0f / 255.0f);
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

TEST(TexturePyramid, LevelsDownToOneTexelOnTheShorterSide) {
  EXPECT_EQ(PyramidLevels(4096, 4096, 9), 9);
  EXPECT_EQ(PyramidLevels(4096, 1024, 20), 11);
  EXPECT_EQ(PyramidLevels(8, 2, 9), 2);
  EXPECT_EQ(PyramidLevels(1, 1, 9), 1);
  EXPECT_EQ(PyramidLevels(64, 64, 1), 1);
}

TEST(TexturePyramid, ATexelIsTheLinearMeanOfFourOfTheLevelAboveRounded) {
  Texture texture = HashTexture(8);
  texture.width = 8;
  texture.height = 8;
  BuildCoarserLevels(&texture, EveryRow(8, 4));
  ASSERT_EQ(texture.levels(), 4);
  const TextureLevel* above = &texture;
  for (const TextureLevel& level : texture.coarser) {
    ASSERT_EQ(level.width, above->width / 2);
    ASSERT_EQ(level.height, above->height / 2);
    for (int j = 0; j < level.height; ++j) {
      for (int i = 0; i < level.width; ++i) {
        for (int c = 0; c < 3; ++c) {
          auto at = [&](int x, int y) { return Linear(above->srgb[(size_t(y) * above->width + x) * 3 + c]); };
          const float mean =
              0.25f * ((at(2 * i, 2 * j) + at(2 * i + 1, 2 * j)) + (at(2 * i, 2 * j + 1) + at(2 * i + 1, 2 * j + 1)));
          EXPECT_EQ(level.srgb[(size_t(j) * level.width + i) * 3 + c], LinearToSrgb8(mean));
        }
      }
    }
    above = &level;
  }
  // At a texel's centre a level's bilinear lookup is that texel; past the coarsest level, the coarsest.
  const TextureLevel& one = texture.coarser[0];
  const Eigen::Vector3f centre = texture.SampleLevel(Eigen::Vector2f(2.5f / 4, 1.5f / 4), 1);
  EXPECT_FLOAT_EQ(centre.x(), Linear(one.srgb[(1 * 4 + 2) * 3]));
  EXPECT_EQ(texture.SampleLevel(Eigen::Vector2f(0.3f, 0.6f), 3), texture.SampleLevel(Eigen::Vector2f(0.3f, 0.6f), 12));
  EXPECT_EQ(texture.SampleLevel(Eigen::Vector2f(0.3f, 0.6f), 0), texture.Sample(Eigen::Vector2f(0.3f, 0.6f)));
}

// The pyramid built from the rows TextureLevelRowsSampled asks for (the rows of level 0 it does not ask for inverted,
// as bytes never decoded would hold anything) reads, at every level, what the pyramid of the whole image
// reads wherever a face's lookup can land.
TEST(TexturePyramid, LookupsInsideTheFacesReadWhatThePyramidOfTheWholeImageReads) {
  const scene::SceneMesh mesh =
      UvMesh({{0.1f, 0.15f, 0.12f}, {0.2f, 0.25f, 0.22f}, {0.3f, 0.31f, 0.35f}, {0.05f, 0.06f, 0.07f}}, {0, 0, 0, 0});
  constexpr int kSize = 256;
  const int levels = PyramidLevels(kSize, kSize, 5);  // down to 16 x 16
  const std::vector<std::vector<uint8_t>> rows = TextureLevelRowsSampled(mesh, 0, kSize, levels);
  ASSERT_EQ(rows.size(), size_t(levels));
  ASSERT_LT(Flagged(rows[0]).size(), size_t(kSize) * 3 / 4);
  for (int k = 0; k < levels; ++k) {
    ASSERT_EQ(rows[size_t(k)].size(), size_t(std::max(1, kSize >> k)));
    // A level's rows include what its own lookups read.
    for (int r : Flagged(TextureRowsSampled(mesh, 0, std::max(1, kSize >> k)))) EXPECT_TRUE(rows[size_t(k)][size_t(r)]);
  }
  Texture full = HashTexture(kSize), partial = HashTexture(kSize), garbage = HashTexture(kSize, true);
  for (size_t i = 0; i < partial.srgb.size(); ++i) {
    if (!rows[0][i / 3 / kSize]) partial.srgb[i] = garbage.srgb[i];
  }
  BuildCoarserLevels(&full, EveryRow(kSize, levels));
  BuildCoarserLevels(&partial, rows);
  for (const Eigen::Vector2f& uv : UvsInsideFaces(mesh, 500, 11)) {
    for (int level = 0; level < levels; ++level)
      ASSERT_EQ(full.SampleLevel(uv, level), partial.SampleLevel(uv, level)) << uv.transpose() << " level " << level;
  }
}

TEST(TexturePyramid, TheLevelIsTheFootprintsLogarithmRounded) {
  EXPECT_EQ(LevelOfFootprint(0.0), 0);
  EXPECT_EQ(LevelOfFootprint(1.0), 0);
  EXPECT_EQ(LevelOfFootprint(std::nan("")), 0);
  // Against log2 rounded, at each boundary (√2 2^k) and between, up to 2^20 texels.
  for (double t = 1.0; t < 1e6; t *= 1.0173) {
    const int expected = int(std::floor(std::log2(t) + 0.5));
    ASSERT_EQ(LevelOfFootprint(t * t), expected) << t;
  }
  for (int k = 1; k < 20; ++k) {
    const double boundary2 = std::ldexp(1.0, 2 * k - 1);  // (√2 2^(k-1))², exactly
    EXPECT_EQ(LevelOfFootprint(std::nextafter(boundary2, 0.0)), k - 1) << k;
    EXPECT_EQ(LevelOfFootprint(boundary2), k) << k;
  }
  EXPECT_GT(LevelOfFootprint(std::numeric_limits<double>::infinity()), 20);  // read as the coarsest
}

TEST(TexturePyramid, TexelsPerMetreOfAFace) {
  // A right triangle with 2 m legs whose uv legs are 0.25 of a 64-texel texture: 16 texels over 2 m.
  scene::SceneMesh mesh;
  mesh.positions_enu_m = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {5, 5, 5}, {6, 5, 5}, {7, 5, 5}};
  mesh.texcoords = {{0, 0}, {0.25f, 0}, {0, 0.25f}, {0, 0}, {0.5f, 0}, {0, 0.5f}};
  mesh.faces = {{0, 1, 2}, {3, 4, 5}};  // the second has no area
  mesh.face_material = {0, 0};
  mesh.materials.resize(1);
  mesh.materials[0].base_color_image = 0;
  mesh.images.resize(1);
  std::vector<Texture> textures(1);
  textures[0].width = textures[0].height = 64;
  textures[0].srgb.resize(64 * 64 * 3);
  const std::vector<float> density = FaceTexelsPerMetre(mesh, textures);
  ASSERT_EQ(density.size(), 2u);
  EXPECT_FLOAT_EQ(density[0], 8.0f);
  EXPECT_EQ(density[1], 0.0f);
  // A face whose material has no texture: 0.
  mesh.materials[0].base_color_image = -1;
  EXPECT_EQ(FaceTexelsPerMetre(mesh, textures)[0], 0.0f);
}

}  // namespace
}  // namespace cinepath::preview
