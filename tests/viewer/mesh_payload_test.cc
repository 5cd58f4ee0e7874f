#include "viewer/mesh_payload.h"

#include <cstring>

#include <gtest/gtest.h>

#include "viewer/deflate.h"

namespace cinepath::viewer {
namespace {

scene::SceneMesh Triangle() {
  scene::SceneMesh mesh;
  mesh.positions_enu_m = {{0, 0, 0}, {100, 0, 0}, {0, 50, 10}};
  mesh.faces = {{0, 1, 2}};
  mesh.colors_linear = {{0, 0, 0}, {1, 1, 1}, {0.5f, 0.2f, 0.0f}};
  return mesh;
}

TEST(MeshPayload, QuantizesInThreeJsFrameOverTheBounds) {
  const MeshPayload payload = EncodeMeshPayload(Triangle());
  EXPECT_EQ(payload.num_vertices, 3u);
  EXPECT_EQ(payload.num_triangles, 1u);
  EXPECT_EQ(payload.index_bytes, 2);
  EXPECT_TRUE(payload.has_colors);
  // three.js frame (e, u, -n): x 0..100, y 0..10, z -50..0
  EXPECT_EQ(payload.min_three_m, (std::array<double, 3>{0, 0, -50}));
  EXPECT_EQ(payload.max_three_m, (std::array<double, 3>{100, 10, 0}));
  const std::string raw = InflateZlib(payload.deflated);
  ASSERT_EQ(raw.size(), 3u * 6 + 3u * 3 + 3u * 2);
  ASSERT_EQ(payload.inflated_bytes, raw.size());
  // Quantized (x, y, z): vertex 0 (0, 0, 65535), vertex 1 (65535, 0, 65535), vertex 2 (0, 65535, 0);
  // as deltas at stride 3: 0 0 65535 | 65535 0 0 | 1 65535 1 (mod 2^16); low bytes first, then high.
  const std::vector<uint32_t> deltas = {0, 0, 65535, 65535, 0, 0, 1, 65535, 1};
  for (size_t i = 0; i < deltas.size(); ++i) {
    EXPECT_EQ(uint8_t(raw[i]), deltas[i] & 0xff) << i;
    EXPECT_EQ(uint8_t(raw[9 + i]), deltas[i] >> 8) << i;
  }
  // Colours: 0 0 0 | 255 255 255 | srgb(0.5) - 255 ... (mod 256)
  EXPECT_EQ(uint8_t(raw[18 + 3]), 255);
  EXPECT_EQ(uint8_t(raw[18 + 6]), uint8_t(LinearToSrgb8(0.5f) - 255));
  // Indices 0 1 2 as deltas 0 1 1, 16-bit planes.
  EXPECT_EQ(std::string(raw.data() + 27, 6), std::string("\x00\x01\x01\x00\x00\x00", 6));
}

TEST(MeshPayload, DeltaBytePlanesWrapAround) {
  EXPECT_EQ(DeltaBytePlanes({5, 3}, 1, 1), std::string("\x05\xfe", 2));
  EXPECT_EQ(DeltaBytePlanes({0x0102, 0x0103}, 2, 1), std::string("\x02\x01\x01\x00", 4));
  EXPECT_EQ(DeltaBytePlanes({0, 0xffffffff}, 4, 1), std::string("\x00\xff\x00\xff\x00\xff\x00\xff", 8));
}

TEST(MeshPayload, WideIndicesPastSixteenBits) {
  scene::SceneMesh mesh;
  for (int i = 0; i < 70000; ++i) mesh.positions_enu_m.emplace_back(i, 0, 0);
  mesh.faces = {{0, 1, 69999}};
  const MeshPayload payload = EncodeMeshPayload(mesh);
  EXPECT_EQ(payload.index_bytes, 4);
  EXPECT_FALSE(payload.has_colors);
  const std::string raw = InflateZlib(payload.deflated);
  ASSERT_EQ(raw.size(), 70000u * 6 + 12);
  // Indices 0 1 69999: deltas 0 1 69998, 32-bit planes; the last delta's bytes sit at 2, 5, 8, 11.
  const std::string planes = raw.substr(70000u * 6);
  const uint32_t last = uint32_t(uint8_t(planes[2])) | uint32_t(uint8_t(planes[5])) << 8 |
                        uint32_t(uint8_t(planes[8])) << 16 | uint32_t(uint8_t(planes[11])) << 24;
  EXPECT_EQ(last, 69998u);
}

TEST(MeshPayload, SrgbTransfer) {
  EXPECT_EQ(LinearToSrgb8(0.0f), 0);
  EXPECT_EQ(LinearToSrgb8(1.0f), 255);
  EXPECT_NEAR(LinearToSrgb8(0.214f), 128, 1);  // mid grey
  EXPECT_EQ(LinearToSrgb8(2.0f), 255);
}

}  // namespace
}  // namespace cinepath::viewer
