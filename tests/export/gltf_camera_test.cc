#include "export/gltf_camera.h"

#include <numbers>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/glb_container.h"
#include "core/json.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

Json JsonOf(const std::string& glb) { return ParseJsonText(SplitGlb(glb, "previs.glb").json, "previs.glb"); }

std::vector<CameraTrack> TwoTracks() {
  return {TrackOfFlight(testing::OrbitPlan(2, 30), "north", "plan.json", true),
          TrackOfFlight(testing::ChasePlan(1, 30), "south", "plan.json", true)};
}

TEST(GltfCamera, ACameraNodePerDroneAnimatedAtEverySample) {
  const std::vector<CameraTrack> tracks = TwoTracks();
  const std::string glb = WriteGltfCamera(tracks);
  const Json doc = JsonOf(glb);
  ASSERT_EQ(doc["cameras"].size(), 2u);
  ASSERT_EQ(doc["nodes"].size(), 2u);
  EXPECT_EQ(doc["nodes"][1]["name"], "south");
  EXPECT_EQ(doc["scenes"][0]["nodes"], Json::array({0, 1}));
  const Json& animation = doc["animations"][0];
  EXPECT_EQ(animation["channels"].size(), 4u);
  for (const Json& sampler : animation["samplers"]) {
    EXPECT_EQ(sampler["interpolation"], "LINEAR");
    EXPECT_EQ(doc["accessors"][sampler["input"].get<int>()]["count"],
              doc["accessors"][sampler["output"].get<int>()]["count"]);
  }
  EXPECT_EQ(doc["accessors"][animation["samplers"][0]["input"].get<int>()]["count"], tracks[0].keys.size());
  EXPECT_NEAR(doc["cameras"][0]["perspective"]["yfov"].get<double>(),
              tracks[0].keys[0].vertical_fov_deg * std::numbers::pi / 180, 1e-12);
  EXPECT_EQ(doc["nodes"][0]["extras"]["focal_length_mm"].size(), tracks[0].keys.size());
  EXPECT_EQ(doc["scenes"][0]["extras"]["frame_rate_hz"], 30.0);
  EXPECT_EQ(doc["buffers"][0]["byteLength"], SplitGlb(glb, "previs.glb").bin.size());
  EXPECT_EQ(WriteGltfCamera(tracks), glb);  // deterministic
}

TEST(GltfCamera, TheScenesBinaryChunkIsKeptByteForByte) {
  const std::string cameras_only = WriteGltfCamera({TwoTracks()[0]});
  // A stand-in scene: a GLB with one node and 12 bytes of its own.
  const std::string scene_bin = std::string("\x01\x02\x03\x04\x05\x06\x07\x08\x09\x0a\x0b\x0c", 12);
  const std::string scene =
      AssembleGlb(R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0],"extras":{"georeferenced":true}}],)"
                  R"("nodes":[{"name":"scene"}],"buffers":[{"byteLength":12}]})",
                  scene_bin);
  const std::string glb = WriteGltfCamera({TwoTracks()[0]}, scene, "scene.glb");
  const GlbChunks chunks = SplitGlb(glb, "previs.glb");
  EXPECT_EQ(chunks.bin.substr(0, 12), scene_bin);
  const Json doc = JsonOf(glb);
  EXPECT_EQ(doc["scenes"][0]["nodes"], Json::array({0, 1}));
  EXPECT_EQ(doc["nodes"][1]["camera"], 0);
  EXPECT_TRUE(doc["scenes"][0]["extras"]["georeferenced"].get<bool>());
  EXPECT_GT(glb.size(), cameras_only.size());
}

TEST(GltfCamera, ASceneWithExternalDataIsRefusedNamingTheFile) {
  const std::string scene =
      AssembleGlb(R"({"asset":{"version":"2.0"},"buffers":[{"uri":"data.bin","byteLength":4}]})", "");
  try {
    WriteGltfCamera(TwoTracks(), scene, "scene.glb");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.glb: buffers:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(WriteGltfCamera(TwoTracks(), "not a glb", "scene.glb"), InputError);
}

}  // namespace
}  // namespace cinepath::exporter
