// `cinepath mesh` with the default options on real photos that are not a nadir survey: the banana set of
// tests/data/photogrammetry/banana (16 hand-held photos of a bunch of bananas on a table, a Nikon D3200
// with real EXIF and a real lens; MIT licence, PROVENANCE.md there), with the COLMAP 3.8 model committed
// beside them and references made from its camera centres. What it asserts:
// - the run ends with exit 0 and a mesh (Poisson, as `auto` picks for views that do not look down);
// - the focal length stays within 2 % of COLMAP's: the geometry resolves it, so the bundle adjustment
//   keeps what the photos measure (1,384.8 px against COLMAP's 1,384.3 px) instead of the EXIF 35 mm
//   equivalent (60 mm: 1,333.3 px at 800 px wide, 3.7 % short: the camera rounds it);
// - the surface faces its cameras: more than half its faces are textured from the photos (3,917 of
//   4,048 measured), which takes a face whose front a photo sees.
//
// Its own executable (it runs the real `cinepath` binary), label "mesh_truth".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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

TEST(RealPhotos, BananaMeshesWithTheFocalLengthThePhotosMeasure) {
  const fs::path data = fs::path(CINEPATH_TEST_DATA_DIR) / "photogrammetry" / "banana";
  ASSERT_TRUE(fs::is_directory(data / "sparse")) << data;
  const fs::path tmp = MakeTempDir("cinepath_real_banana");
  ASSERT_FALSE(tmp.empty());
  const fs::path out = tmp / "scene";
  const std::string command = ShellQuote(CINEPATH_BINARY) + " mesh --colmap " + ShellQuote((data / "sparse").string()) +
                              " --refs " + ShellQuote((data / "refs_gps.txt").string()) + " --images " +
                              ShellQuote((data / "images").string()) + " -o " + ShellQuote(out.string()) +
                              " --no-timestamp 2> " + ShellQuote((tmp / "stderr.txt").string());
  const int rc = std::system(command.c_str());
  ASSERT_EQ(rc, 0) << command << "\n" << ReadText(tmp / "stderr.txt");

  const cinepath::Json scene = cinepath::Json::parse(ReadText(out / "scene.json"));
  const auto& surface = scene["surface"];
  EXPECT_GT(surface["output"]["faces"].get<int64_t>(), 500);
  bool poisson = false;
  for (const auto& step : surface["steps"]) poisson = poisson || step["step"] == "poisson";
  EXPECT_TRUE(poisson);

  const auto& ba = scene["georeferencing"]["bundle_adjustment"];
  const auto& focal = ba["focal_length"][0];
  const double colmap_px = focal["before_px"].get<double>(), chosen_px = focal["after_px"].get<double>();
  std::printf("banana: focal %.1f px (COLMAP %.1f px, EXIF prior %s), depth relief %.3f, view spread %.1f deg\n",
              chosen_px, colmap_px, focal["prior_px"].dump().c_str(), ba["depth_relief_ratio"].get<double>(),
              ba["view_axis_spread_deg"].get<double>());
  EXPECT_TRUE(ba["geometry_resolves_focal"].get<bool>());
  EXPECT_FALSE(focal["held_at_prior"].get<bool>());
  EXPECT_LT(std::abs(chosen_px / colmap_px - 1), 0.02);

  const auto& texture = scene["texture"];
  std::printf("banana: %s\n", texture.dump().substr(0, 400).c_str());
  if (texture.contains("faces_textured") && texture.contains("faces")) {
    EXPECT_GT(texture["faces_textured"].get<double>(), 0.5 * texture["faces"].get<double>());
  }
  fs::remove_all(tmp);
}

}  // namespace
