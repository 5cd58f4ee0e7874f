#include "scene/glb_reader.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/file_io.h"
#include "scene/tinygltf_config.h"

namespace cinepath::scene {
namespace {

namespace fs = std::filesystem;

// A GLB built with tinygltf: one node with `node` transform, one primitive with the given mode.
std::string MakeGlb(const std::vector<float>& positions_gltf, const std::vector<uint16_t>& indices, int mode,
                    const std::function<void(tinygltf::Node&)>& node_setup = {}) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  tinygltf::Buffer buffer;
  const size_t pos_bytes = positions_gltf.size() * sizeof(float);
  buffer.data.resize(pos_bytes + indices.size() * sizeof(uint16_t));
  std::memcpy(buffer.data.data(), positions_gltf.data(), pos_bytes);
  std::memcpy(buffer.data.data() + pos_bytes, indices.data(), indices.size() * sizeof(uint16_t));
  model.buffers.push_back(buffer);
  tinygltf::BufferView pv;
  pv.buffer = 0;
  pv.byteOffset = 0;
  pv.byteLength = pos_bytes;
  model.bufferViews.push_back(pv);
  tinygltf::BufferView iv;
  iv.buffer = 0;
  iv.byteOffset = pos_bytes;
  iv.byteLength = indices.size() * sizeof(uint16_t);
  model.bufferViews.push_back(iv);
  tinygltf::Accessor pa;
  pa.bufferView = 0;
  pa.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  pa.type = TINYGLTF_TYPE_VEC3;
  pa.count = positions_gltf.size() / 3;
  model.accessors.push_back(pa);
  tinygltf::Accessor ia;
  ia.bufferView = 1;
  ia.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  ia.type = TINYGLTF_TYPE_SCALAR;
  ia.count = indices.size();
  model.accessors.push_back(ia);
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = 0;
  prim.indices = 1;
  prim.mode = mode;
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  if (node_setup) node_setup(node);
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  EXPECT_TRUE(writer.WriteGltfSceneToStream(&model, out, false, true));
  return out.str();
}

TEST(GlbReader, GltfYUpBecomesEnuZUp) {
  // glTF (x, y, z) = (e, u, -n): a triangle at glTF (1, 2, -3) is at ENU (1, 3, 2).
  const std::string glb = MakeGlb({1, 2, -3, 2, 2, -3, 1, 2, -4}, {0, 1, 2}, 4);
  const SceneMesh mesh = ReadGlbBytes(glb, "t.glb");
  ASSERT_EQ(mesh.num_faces(), 1u);
  EXPECT_TRUE(mesh.positions_enu_m[0].isApprox(Eigen::Vector3d(1, 3, 2)));
  EXPECT_TRUE(mesh.positions_enu_m[2].isApprox(Eigen::Vector3d(1, 4, 2)));
  // Counter-clockwise seen from above in glTF stays counter-clockwise seen from above in ENU.
  const Eigen::Vector3d n =
      (mesh.positions_enu_m[1] - mesh.positions_enu_m[0]).cross(mesh.positions_enu_m[2] - mesh.positions_enu_m[0]);
  EXPECT_GT(n.z(), 0);
  EXPECT_FALSE(mesh.has_colors());
}

TEST(GlbReader, NodeTransformsAreApplied) {
  const std::string glb = MakeGlb({0, 0, 0, 1, 0, 0, 0, 0, -1}, {0, 1, 2}, 4, [](tinygltf::Node& n) {
    n.translation = {10, 20, 30};
    n.scale = {2, 2, 2};
  });
  const SceneMesh mesh = ReadGlbBytes(glb, "t.glb");
  // glTF (1, 0, 0) -> scaled (2, 0, 0) -> translated (12, 20, 30) -> ENU (12, -30, 20).
  EXPECT_TRUE(mesh.positions_enu_m[1].isApprox(Eigen::Vector3d(12, -30, 20)));
}

TEST(GlbReader, StripsAndFansBecomeTriangles) {
  const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 0, 0, -1, 1, 0, -1};
  EXPECT_EQ(ReadGlbBytes(MakeGlb(quad, {0, 1, 2, 3}, 5), "strip.glb").num_faces(), 2u);
  EXPECT_EQ(ReadGlbBytes(MakeGlb(quad, {0, 1, 3, 2}, 6), "fan.glb").num_faces(), 2u);
}

TEST(GlbReader, RefusesWhatIsNotAGlbOrHasNoTriangles) {
  EXPECT_THROW(ReadGlbBytes("not a glb at all", "x.glb"), InputError);
  // Points only (mode 0): no triangles.
  try {
    ReadGlbBytes(MakeGlb({0, 0, 0, 1, 0, 0, 0, 0, -1}, {0, 1, 2}, 0), "points.glb");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "points.glb: holds no triangles");
  }
}

TEST(GlbReader, IndexOutOfRangeIsAnInputErrorNamingTheAccessor) {
  try {
    ReadGlbBytes(MakeGlb({0, 0, 0, 1, 0, 0, 0, 0, -1}, {0, 1, 7}, 4), "bad.glb");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.glb: accessors[1]: index 7 out of range"), std::string::npos) << e.what();
  }
}

TEST(GlbReader, ReadsTheBundledGoldenScene) {
  // The mesh golden case's output (6 Brighton Beach photos): what `cinepath mesh` writes.
  const fs::path glb = fs::path(CINEPATH_SOURCE_DIR) / "tests/golden/mesh/brighton6_binary/expected/scene.glb";
  const SceneMesh mesh = ReadGlbFile(glb);
  EXPECT_GT(mesh.num_faces(), 1000u);
  EXPECT_TRUE(mesh.has_colors());
  EXPECT_EQ(mesh.colors_linear.size(), mesh.num_vertices());
  // The ground lies about 35-40 m below the camera-centred origin, and the scene spans tens of metres.
  const Eigen::AlignedBox3d box = mesh.Bounds();
  EXPECT_LT(box.max().z(), -20);
  EXPECT_GT(box.sizes().x(), 20);
}

// Found by fuzz_glb: a Draco GLB cut short, whose BIN chunk claims 4 bytes more than the file holds;
// tinygltf copied past the end. The container is now checked first, and every cut is an InputError.
TEST(GlbReader, TruncatedOrInconsistentContainerIsAnInputError) {
  const fs::path dir = fs::path(CINEPATH_SOURCE_DIR) / "tests/fuzz/corpus/fuzz_glb";
  const std::string crash = ReadFileToString(dir / "crash_2026-11-24_bin_chunk_past_the_end.glb");
  EXPECT_THROW(ReadGlbBytes(crash, "crash.glb"), InputError);
  const std::string whole = ReadFileToString(dir / "brighton6_draco.glb");
  EXPECT_GT(ReadGlbBytes(whole, "whole.glb").num_faces(), 100u);
  for (size_t cut : {size_t(13), size_t(24), whole.size() / 2, whole.size() - 4, whole.size() - 1}) {
    try {
      ReadGlbBytes(whole.substr(0, cut), "cut.glb");
      ADD_FAILURE() << "a GLB cut to " << cut << " bytes was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cut.glb"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace cinepath::scene
