#include "photogrammetry/gltf/gltf_writer.h"

#include <cstring>
#include <string>

#include <draco/compression/decode.h>
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/three_frame.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

// A GLB split into its JSON and BIN chunks (glTF 2.0 §4.4), checked on the way.
struct Glb {
  Json json;
  std::string bin;
};

uint32_t ReadU32(const std::string& bytes, size_t offset) {
  uint32_t value = 0;
  std::memcpy(&value, bytes.data() + offset, 4);
  return value;
}

Glb ParseGlb(const std::string& bytes) {
  Glb glb;
  EXPECT_GE(bytes.size(), 20u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(ReadU32(bytes, 4), 2u);
  EXPECT_EQ(ReadU32(bytes, 8), bytes.size());
  const uint32_t json_length = ReadU32(bytes, 12);
  EXPECT_EQ(ReadU32(bytes, 16), 0x4E4F534Au);  // "JSON"
  EXPECT_EQ(json_length % 4, 0u);
  glb.json = Json::parse(bytes.substr(20, json_length));
  const size_t bin_header = 20 + json_length;
  if (bin_header + 8 <= bytes.size()) {
    const uint32_t bin_length = ReadU32(bytes, bin_header);
    EXPECT_EQ(ReadU32(bytes, bin_header + 4), 0x004E4942u);  // "BIN\0"
    glb.bin = bytes.substr(bin_header + 8, bin_length);
  }
  return glb;
}

TriangleMesh OneTriangle() {
  TriangleMesh mesh;
  mesh.vertices_m = {{1.0, 2.0, 3.0}, {4.0, 2.0, 3.0}, {1.0, 6.0, 5.0}};
  mesh.faces = {{0, 1, 2}};
  mesh.colors_rgb = {{255, 0, 0}, {0, 128, 0}, {0, 0, 10}};
  return mesh;
}

TEST(LinearFromSrgb8, MatchesTheSrgbTransferFunction) {
  EXPECT_FLOAT_EQ(LinearFromSrgb8(0), 0.0f);
  EXPECT_FLOAT_EQ(LinearFromSrgb8(255), 1.0f);
  EXPECT_NEAR(LinearFromSrgb8(10), 10.0 / 255.0 / 12.92, 1e-7);  // linear segment
  EXPECT_NEAR(LinearFromSrgb8(128), 0.2158605, 1e-6);            // ((0.50196+0.055)/1.055)^2.4
}

TEST(WriteGlb, PlainGlbHoldsPositionsIndicesColoursAndExtras) {
  GlbWriteOptions options;
  options.extras = Json::parse(R"({"origin": {"lat_deg": 47.5, "lon_deg": 8.25, "height_m": 400.0}})");
  const Glb glb = ParseGlb(WriteGlb(OneTriangle(), options));
  const Json& j = glb.json;
  EXPECT_EQ(j["asset"]["version"], "2.0");
  EXPECT_DOUBLE_EQ(j["asset"]["extras"]["origin"]["lat_deg"].get<double>(), 47.5);
  EXPECT_DOUBLE_EQ(j["scenes"][0]["extras"]["origin"]["lon_deg"].get<double>(), 8.25);
  const Json& primitive = j["meshes"][0]["primitives"][0];
  const Json& positions = j["accessors"][primitive["attributes"]["POSITION"].get<int>()];
  EXPECT_EQ(positions["count"], 3);
  EXPECT_EQ(positions["componentType"], 5126);
  // bounds in the glTF frame: x = e in [1, 4], y = u in [3, 5], z = −n in [−6, −2]
  EXPECT_EQ(positions["min"], Json::array({1.0, 3.0, -6.0}));
  EXPECT_EQ(positions["max"], Json::array({4.0, 5.0, -2.0}));

  const Json& view = j["bufferViews"][positions["bufferView"].get<int>()];
  const size_t offset = view.value("byteOffset", 0);
  float xyz[9];
  std::memcpy(xyz, glb.bin.data() + offset, sizeof(xyz));
  EXPECT_FLOAT_EQ(xyz[3], 4.0f);   // vertex 1: e
  EXPECT_FLOAT_EQ(xyz[7], 5.0f);   // vertex 2: u
  EXPECT_FLOAT_EQ(xyz[8], -6.0f);  // vertex 2: −n

  const Json& indices = j["accessors"][primitive["indices"].get<int>()];
  EXPECT_EQ(indices["count"], 3);
  EXPECT_EQ(indices["componentType"], 5125);

  const Json& colors = j["accessors"][primitive["attributes"]["COLOR_0"].get<int>()];
  const Json& color_view = j["bufferViews"][colors["bufferView"].get<int>()];
  float rgb[9];
  std::memcpy(rgb, glb.bin.data() + color_view.value("byteOffset", 0), sizeof(rgb));
  EXPECT_FLOAT_EQ(rgb[0], 1.0f);
  EXPECT_FLOAT_EQ(rgb[4], LinearFromSrgb8(128));
  EXPECT_FALSE(j.contains("extensionsUsed"));
}

TEST(WriteGlb, DracoGlbDecodesToTheSameMesh) {
  const TriangleMesh mesh = testing::TerrainGrid(40, 30, 2.0);
  GlbWriteOptions options;
  options.draco = true;
  const std::string bytes = WriteGlb(mesh, options);
  const Glb glb = ParseGlb(bytes);
  const Json& j = glb.json;
  EXPECT_EQ(j["extensionsUsed"], Json::array({"KHR_draco_mesh_compression"}));
  EXPECT_EQ(j["extensionsRequired"], Json::array({"KHR_draco_mesh_compression"}));
  const Json& primitive = j["meshes"][0]["primitives"][0];
  const Json& ext = primitive["extensions"]["KHR_draco_mesh_compression"];
  const Json& view = j["bufferViews"][ext["bufferView"].get<int>()];
  const Json& positions = j["accessors"][primitive["attributes"]["POSITION"].get<int>()];
  EXPECT_FALSE(positions.contains("bufferView"));

  draco::DecoderBuffer buffer;
  buffer.Init(glb.bin.data() + view.value("byteOffset", 0), view["byteLength"].get<size_t>());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  ASSERT_TRUE(decoded.ok());
  const draco::Mesh& out = *decoded.value();
  EXPECT_EQ(out.num_faces(), mesh.num_faces());
  EXPECT_EQ(out.num_points(), mesh.num_vertices());
  EXPECT_EQ(positions["count"].get<size_t>(), out.num_points());
  EXPECT_EQ(j["accessors"][primitive["indices"].get<int>()]["count"].get<size_t>(), 3 * mesh.num_faces());
  // Decoded positions are within the 16-bit quantization step of the glTF-frame input.
  const auto* attribute = out.GetAttributeByUniqueId(ext["attributes"]["POSITION"].get<uint32_t>());
  ASSERT_NE(attribute, nullptr);
  const double extent_m = 78.0;  // largest side of the 78 m × 58 m grid
  float first[3];
  // Find the decoded point closest to vertex 0 in the glTF frame.
  const Eigen::Vector3f want = ThreeFromEnu(mesh.vertices_m[0]).cast<float>();
  double best = 1e9;
  for (uint32_t i = 0; i < out.num_points(); ++i) {
    attribute->GetMappedValue(draco::PointIndex(i), first);
    best = std::min<double>(best, (Eigen::Vector3f(first[0], first[1], first[2]) - want).norm());
  }
  EXPECT_LT(best, 2 * extent_m / 65536.0);
  EXPECT_LT(bytes.size(), WriteGlb(mesh, GlbWriteOptions{}).size() / 3);
}

TEST(WriteGlb, BytesAreDeterministic) {
  const TriangleMesh mesh = testing::TerrainGrid(20, 20, 1.0);
  GlbWriteOptions draco;
  draco.draco = true;
  EXPECT_EQ(WriteGlb(mesh, GlbWriteOptions{}), WriteGlb(mesh, GlbWriteOptions{}));
  EXPECT_EQ(WriteGlb(mesh, draco), WriteGlb(mesh, draco));
}

TEST(WriteGlb, RejectsEmptyMeshesAndBadIndices) {
  EXPECT_THROW(WriteGlb(TriangleMesh{}, GlbWriteOptions{}), InputError);
  TriangleMesh bad = OneTriangle();
  bad.faces[0][2] = 7;
  EXPECT_THROW(WriteGlb(bad, GlbWriteOptions{}), InputError);
  GlbWriteOptions not_object;
  not_object.extras = Json::array({1, 2});
  EXPECT_THROW(WriteGlb(OneTriangle(), not_object), InputError);
}

}  // namespace
}  // namespace cinepath::photogrammetry
