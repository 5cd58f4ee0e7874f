#include "viewer/previs_page.h"

#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/file_io.h"
#include "core/json.h"
#include "core/number_format.h"

namespace cinepath::viewer {
namespace {

const std::filesystem::path kSource = CINEPATH_SOURCE_DIR;
const std::filesystem::path kLookDownPlan = kSource / "tests/preview/data/look_down_plan.json";  // no origin
const std::filesystem::path kGoldenScene = kSource / "tests/golden/mesh/brighton6_binary/expected/scene.json";

TEST(FillTemplate, ReplacesPlaceholdersOnce) {
  EXPECT_EQ(FillTemplate("<@A@|@B@|a@b.c>", {{"A", "@B@"}, {"B", "x"}}), "<@B@|x|a@b.c>");
}

TEST(JsonForScriptElement, EscapesClosingTags) {
  EXPECT_EQ(JsonForScriptElement(R"({"a":"</script>"})"), R"({"a":"<\/script>"})");
}

TEST(PrevisPage, PlanWithoutOriginOverAScene) {
  ViewOptions options;
  options.plan = kLookDownPlan;
  options.scene = kGoldenScene;
  const PrevisPage page = BuildPrevisPage(options);
  EXPECT_GT(page.mesh_triangles, 1000u);
  EXPECT_EQ(page.inputs.size(), 3u);  // plan, scene.json, scene.glb
  EXPECT_NE(page.html.find("<script type=\"importmap\">"), std::string::npos);
  EXPECT_EQ(page.html.find("@DATA_JSON@"), std::string::npos);
  EXPECT_EQ(page.html.find("http://"), std::string::npos);  // nothing to fetch
  // The same bytes each run.
  EXPECT_EQ(BuildPrevisPage(options).html, page.html);
}

TEST(PrevisPage, ThePhotosOfTheSceneAreMarked) {
  // The golden scene records its 6 photos (scene.json `cameras`); the page carries each position, in
  // three.js's frame (e, u, -n), to the millimetre.
  ViewOptions options;
  options.plan = kLookDownPlan;
  options.scene = kGoldenScene;
  const std::string html = BuildPrevisPage(options).html;
  const Json scene = ParseJsonFile(kGoldenScene);
  ASSERT_EQ(scene["cameras"].size(), 6u);
  for (const Json& camera : scene["cameras"]) {
    EXPECT_NE(html.find("\"name\":\"" + camera["image"].get<std::string>() + "\""), std::string::npos)
        << camera["image"];
  }
  const Json& p = scene["cameras"][0]["position_enu_m"];
  const std::string three = "[" + FormatShortest(RoundToDecimals(p[0].get<double>(), 3)) + "," +
                            FormatShortest(RoundToDecimals(p[2].get<double>(), 3)) + "," +
                            FormatShortest(RoundToDecimals(-p[1].get<double>(), 3)) + "]";
  EXPECT_NE(html.find("\"position_m\":" + three), std::string::npos) << three;
}

TEST(PrevisPage, PlanAloneViewsInLocalMetres) {
  ViewOptions options;
  options.plan = kLookDownPlan;
  const PrevisPage page = BuildPrevisPage(options);
  EXPECT_EQ(page.mesh_triangles, 0u);
  EXPECT_NE(page.html.find("\"origin\":null"), std::string::npos);
  EXPECT_NE(page.html.find("id=\"previs-mesh-info\">null<"), std::string::npos);
}

TEST(PrevisPage, MissingMeshIsBadInput) {
  const auto dir = std::filesystem::path(testing::TempDir()) / "viewer_missing_mesh";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"mesh": "gone.glb"})";
  ViewOptions options;
  options.plan = kLookDownPlan;
  options.scene = dir / "scene.json";
  try {
    BuildPrevisPage(options);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh"), std::string::npos) << e.what();
  }
}

TEST(PrevisPage, FramesAreInlined) {
  const auto dir = std::filesystem::path(testing::TempDir()) / "viewer_page_frames";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "frame_000003.png") << "PNG";
  ViewOptions options;
  options.plan = kLookDownPlan;
  options.frames_dir = dir;
  const PrevisPage page = BuildPrevisPage(options);
  EXPECT_EQ(page.frames_inlined, 1u);
  EXPECT_NE(page.html.find("{\"3\":\"data:image/png;base64,UE5H\"}"), std::string::npos);
}

}  // namespace
}  // namespace cinepath::viewer
