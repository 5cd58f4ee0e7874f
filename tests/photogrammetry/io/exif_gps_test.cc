#include "photogrammetry/io/exif_gps.h"
#include "tests/photogrammetry/synthetic_colmap.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "core/error.h"
#include "core/plugin.h"
#include "photogrammetry/io/exif_gps_abi.h"
#include "tests/photogrammetry/test_paths.h"

namespace cinepath::photogrammetry {
namespace {

class ExifGps : public ::testing::Test {
 protected:
  void SetUp() override { setenv("CINEPATH_PLUGIN_DIR", CINEPATH_TEST_PLUGIN_DIR, 1); }
};

// A real DJI Phantom 3 photo (tests/data/colmap/PROVENANCE.md); values as `iinfo -v` prints them and
// as brighton_beach/refs_gps.txt lists them.
TEST_F(ExifGps, ReadsGpsAndFocalLengthOfARealDjiPhoto) {
  const ExifInfo e = ReadExif(testing::TestDataDir() / "colmap" / "exif" / "DJI_0018.JPG");
  ASSERT_TRUE(e.has_gps);
  EXPECT_NEAR(e.lat_deg, 46.8426070833, 1e-6);
  EXPECT_NEAR(e.lon_deg, -91.9945598889, 1e-6);  // GPSLongitudeRef W
  EXPECT_NEAR(e.alt_m, 198.309, 1e-3);
  ASSERT_TRUE(e.focal_length_mm);
  EXPECT_NEAR(*e.focal_length_mm, 3.61, 1e-6);
  EXPECT_EQ(e.focal_length_35mm_mm.value_or(0), 20);
  EXPECT_EQ(e.make, "DJI");
  EXPECT_EQ(e.model, "FC300S");
  EXPECT_EQ(e.width_px, 1600);
  EXPECT_EQ(e.height_px, 900);

  // FC300S: 3.61 mm on a 6.317 mm sensor at 1600 px -> 914.3 px.
  const auto prior = FocalPriorFromExif(e, 1600, std::nullopt);
  ASSERT_TRUE(prior);
  EXPECT_NEAR(prior->focal_px, 914.36, 0.01);
  // A given sensor width wins; without any, the 35 mm equivalent: 20 / 36 * 1600.
  EXPECT_NEAR(FocalPriorFromExif(e, 1600, 6.17)->focal_px, *e.focal_length_mm / 6.17 * 1600, 1e-9);
  ExifInfo unknown = e;
  unknown.model = "SOMETHING";
  EXPECT_NEAR(FocalPriorFromExif(unknown, 1600, std::nullopt)->focal_px, 20.0 / 36 * 1600, 1e-9);

  const auto refs = ReferencesFromExif(testing::TestDataDir() / "colmap" / "exif", {e});
  ASSERT_EQ(refs.size(), 1u);
  EXPECT_EQ(refs[0].image_name, "DJI_0018.JPG");
}

TEST_F(ExifGps, UnreadableImageIsAnInputErrorNamingTheFile) {
  const auto dir = testing::ScratchDir("exif_bad");
  const auto path = dir / "broken.jpg";
  testing::WriteFile(path, "not a jpeg");
  try {
    ReadExif(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.jpg: cannot read EXIF"), std::string::npos) << e.what();
  }
}

TEST_F(ExifGps, MissingImagesFolderIsAnInputError) {
  try {
    ReadExifFolder("/nonexistent-images", {"a.jpg"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-images: not a directory"), std::string::npos);
  }
}

// core/plugin.h: a missing plugin is a RuntimeError that says where it looked.
TEST_F(ExifGps, MissingPluginSaysWhereItLooked) {
  setenv("CINEPATH_PLUGIN_DIR", "/nonexistent-plugin-dir", 1);
  try {
    LoadPluginSymbol("libcinepath_does_not_exist.so", "x");
    FAIL();
  } catch (const RuntimeError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("plugin libcinepath_does_not_exist.so not found"), std::string::npos) << msg;
    EXPECT_NE(msg.find("/nonexistent-plugin-dir/libcinepath_does_not_exist.so"), std::string::npos) << msg;
  }
  // The real plugin, found through CINEPATH_PLUGIN_DIR, has the entry point but not other symbols.
  setenv("CINEPATH_PLUGIN_DIR", CINEPATH_TEST_PLUGIN_DIR, 1);
  std::string from;
  EXPECT_NE(LoadPluginSymbol(kCinepathExifPluginFile, kCinepathExifReadSymbol, &from), nullptr);
  EXPECT_NE(from.find(kCinepathExifPluginFile), std::string::npos);
  EXPECT_THROW(LoadPluginSymbol(kCinepathExifPluginFile, "no_such_symbol"), RuntimeError);
}

}  // namespace
}  // namespace cinepath::photogrammetry
