#include "core/scene_file.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "tests/support/input_error.h"

#include "core/error.h"

namespace cinepath {
namespace {

namespace fs = std::filesystem;

TEST(SceneFile, ReadsOriginAndResolvesTheMeshBesideIt) {
  const SceneFile s = ParseSceneFile(Json::parse(R"({"format": "cinepath.scene", "version": 1, "mesh": "scene.glb",
                      "origin": {"lat_deg": 46.8, "lon_deg": -91.9, "height_m": 198.5, "geoid_model": "EGM96"}})"),
                                     "scene.json", "/data/beach");
  ASSERT_TRUE(s.origin);
  EXPECT_DOUBLE_EQ(s.origin->lat_deg, 46.8);
  EXPECT_EQ(s.mesh->string(), "/data/beach/scene.glb");
}

TEST(SceneFile, AHandWrittenSceneNeedsOnlyMeshAndOrigin) {
  const SceneFile s = ParseSceneFile(Json::parse(R"({"mesh": "m.glb"})"), "s.json", "d");
  EXPECT_FALSE(s.origin);
  EXPECT_EQ(testing::InputErrorMessage([&] { s.RequireOrigin(); }),
            "s.json: origin: missing ({\"lat_deg\", \"lon_deg\", \"height_m\"})");
}

TEST(SceneFile, BadInputNamesTheFileAndTheKey) {
  auto parse = [](const char* text) { ParseSceneFile(Json::parse(text), "scene.json", "."); };
  EXPECT_EQ(testing::InputErrorMessage([&] { parse(R"({"format": "other"})"); }),
            "scene.json: format: expected \"cinepath.scene\", got \"other\"");
  EXPECT_EQ(testing::InputErrorMessage([&] { parse(R"({"version": 2})"); }),
            "scene.json: version: unsupported scene version 2 (this build reads 1)");
  EXPECT_EQ(testing::InputErrorMessage([&] { parse(R"({"origin": {"lat_deg": 91, "lon_deg": 0, "height_m": 0}})"); }),
            "scene.json: origin.lat_deg: must be in [-90, 90]");
  EXPECT_EQ(testing::InputErrorMessage([&] { parse(R"([1])"); }), "scene.json: expected a scene (a JSON object)");
  // Every number a stage reads: the origin's height, the photos' positions (view draws them).
  EXPECT_EQ(
      testing::InputErrorMessage([&] { parse(R"({"origin": {"lat_deg": 1, "lon_deg": 0, "height_m": -1e308}})"); }),
      "scene.json: origin.height_m: must be in [-12000, 100000] m");
  EXPECT_EQ(testing::InputErrorMessage(
                [&] { parse(R"({"cameras": [{"image": "a.jpg", "position_enu_m": [0, 1e300, 0]}]})"); }),
            "scene.json: cameras[0].position_enu_m[1]: must lie within 1e7 m of the origin, got 1e+300");
  EXPECT_EQ(testing::InputErrorMessage([&] { parse(R"({"cameras": [{"position_enu_m": [0, "x", 0]}]})"); }),
            "scene.json: cameras[0].position_enu_m[1]: expected a number, found a string");
  EXPECT_NO_THROW(parse(R"({"cameras": [{"image": "a.jpg", "position_enu_m": [1e7, -1e7, 0]}, "not an object"]})"));
}

TEST(SceneFile, AMissingMeshIsNamed) {
  const SceneFile s = ParseSceneFile(Json::parse(R"({"mesh": "nowhere.glb"})"), "scene.json", "/nonexistent");
  EXPECT_EQ(testing::InputErrorMessage([&] { s.RequireMesh(); }),
            "scene.json: mesh: '/nonexistent/nowhere.glb' does not exist or is not a file");
  const SceneFile none = ParseSceneFile(Json::parse(R"({})"), "scene.json", ".");
  EXPECT_NE(testing::InputErrorMessage([&] { none.RequireMesh(); }).find("scene.json: mesh: missing"),
            std::string::npos);
}

}  // namespace
}  // namespace cinepath
