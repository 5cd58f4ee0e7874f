// `cinepath mesh --surface poisson` on the bundled sample (data/brighton_beach, the 18-photo COLMAP
// model and its GPS references): CGAL's Poisson once stopped inside its surface mesher on it ("already
// inserted on surface"); now, coincident points merged first (surface_poisson.h), it meshes at the
// first attempt. What it asserts: exit 0, the Poisson step ran as asked (no fallback to
// the height field, no coarser retry) and left a mesh. ~21 s of CPU (docs/mesh.md, "Poisson on the
// bundled sample").
//
// Its own executable (it runs the real `cinepath` binary), label "mesh_truth".
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/json.h"
#include "tests/support/command_line.h"

namespace {

namespace fs = std::filesystem;
using cinepath::testing::MakeTempDir;
using cinepath::testing::ReadText;
using cinepath::testing::ShellQuote;

TEST(SamplePoisson, TheBundledSampleMeshesWithPoisson) {
  const fs::path data = fs::path(CINEPATH_TEST_DATA_DIR).parent_path().parent_path() / "data" / "brighton_beach";
  ASSERT_TRUE(fs::is_directory(data / "colmap" / "sparse_default")) << data;
  const fs::path tmp = MakeTempDir("cinepath_sample_poisson");
  ASSERT_FALSE(tmp.empty());
  const fs::path out = tmp / "scene";
  const std::string command =
      ShellQuote(CINEPATH_BINARY) + " mesh --colmap " + ShellQuote((data / "colmap" / "sparse_default").string()) +
      " --refs " + ShellQuote((data / "refs_gps.txt").string()) + " --surface poisson -o " + ShellQuote(out.string()) +
      " --no-timestamp 2> " + ShellQuote((tmp / "stderr.txt").string());
  const int rc = std::system(command.c_str());
  ASSERT_EQ(rc, 0) << command << "\n" << ReadText(tmp / "stderr.txt");

  const cinepath::Json scene = cinepath::Json::parse(ReadText(out / "scene.json"));
  const cinepath::Json* poisson = nullptr;
  for (const auto& step : scene["surface"]["steps"]) {
    if (step["step"] == "poisson") poisson = &step;
  }
  ASSERT_NE(poisson, nullptr) << scene["surface"].dump();
  EXPECT_EQ((*poisson)["method_requested"], "poisson");
  EXPECT_FALSE(poisson->contains("fallback_from"));
  EXPECT_FALSE(poisson->contains("coarser_after_failure"));
  EXPECT_GT(scene["surface"]["output"]["faces"].get<int64_t>(), 1000);
  fs::remove_all(tmp);
}

}  // namespace
