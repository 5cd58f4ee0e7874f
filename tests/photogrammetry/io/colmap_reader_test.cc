#include "photogrammetry/io/colmap_reader.h"

#include <gtest/gtest.h>

#include "tests/support/input_error.h"

#include "core/error.h"
#include "core/file_io.h"
#include "photogrammetry/georef/camera_models.h"
#include "tests/photogrammetry/synthetic_colmap.h"
#include "tests/photogrammetry/test_paths.h"

namespace cinepath::photogrammetry {
namespace {

using testing::MakeSyntheticScene;
using testing::SyntheticOptions;

SyntheticOptions SmallScene() {
  SyntheticOptions o;
  o.rows = 2;
  o.cols = 3;
  o.num_points = 60;
  return o;
}

TEST(ColmapReader, TextAndBinaryOfEveryCameraModelGiveTheSameModel) {
  for (int model_id = 0; model_id < kNumCameraModels; ++model_id) {
    SyntheticOptions o = SmallScene();
    o.model_id = model_id;
    const int n = CameraModelNumParams(model_id);
    o.params.assign(n, 0.0);
    const bool single = CameraModelHasSingleFocal(model_id);
    o.params[0] = 900;
    if (!single) o.params[1] = 905;
    o.params[single ? 1 : 2] = 800;
    o.params[single ? 2 : 3] = 450;
    for (int i : CameraModelExtraIndices(model_id)) o.params[i] = 0.001 * (i + 1);
    if (model_id == static_cast<int>(CameraModelId::kFov)) o.params[4] = 0.9;
    const auto scene = MakeSyntheticScene(o);
    const auto dir = testing::ScratchDir("models_" + std::to_string(model_id));
    testing::WriteColmapText(scene.model, dir / "txt");
    testing::WriteColmapBinary(scene.model, dir / "bin");
    EXPECT_EQ(DetectColmapFormat(dir / "txt"), ColmapFormat::kText);
    EXPECT_EQ(DetectColmapFormat(dir / "bin"), ColmapFormat::kBinary);
    const ColmapModel text = ReadColmapModel(dir / "txt");
    const ColmapModel binary = ReadColmapModel(dir / "bin");
    EXPECT_TRUE(text == binary) << CameraModelName(model_id);
    ASSERT_EQ(binary.cameras.size(), 1u);
    EXPECT_EQ(binary.cameras.at(1).model_id, model_id);
    EXPECT_EQ(binary.cameras.at(1).params, o.params);
    EXPECT_EQ(binary.images.size(), 6u);
    EXPECT_EQ(binary.points3d.size(), scene.model.points3d.size());
    EXPECT_GT(binary.points3d.size(), 30u);
    for (const auto& [id, p] : binary.points3d) EXPECT_EQ(p.xyz, scene.model.points3d.at(id).xyz);
  }
}

TEST(ColmapReader, BinaryPreferredWhenBothExist) {
  auto scene = MakeSyntheticScene(SmallScene());
  const auto dir = testing::ScratchDir("both");
  testing::WriteColmapBinary(scene.model, dir);
  scene.model.points3d.erase(scene.model.points3d.begin());  // the text copy differs
  for (auto& [id, im] : scene.model.images)
    for (auto& pid : im.point3d_ids)
      if (!scene.model.points3d.contains(pid)) pid = kInvalidPoint3DId;
  testing::WriteColmapText(scene.model, dir);
  EXPECT_EQ(DetectColmapFormat(dir), ColmapFormat::kBinary);
  EXPECT_EQ(ReadColmapModel(dir).points3d.size(), scene.model.points3d.size() + 1);
  EXPECT_EQ(ReadColmapModel(dir, ColmapFormat::kText).points3d.size(), scene.model.points3d.size());
}

TEST(ColmapReader, MissingFilesNameTheFolder) {
  const auto dir = testing::ScratchDir("empty");
  const std::string msg = cinepath::testing::InputErrorMessage([&] { ReadColmapModel(dir); });
  EXPECT_NE(msg.find("not a COLMAP sparse model"), std::string::npos) << msg;
  EXPECT_NE(msg.find(dir.string()), std::string::npos) << msg;
}

// A workspace root or its sparse/ folder finds the only model COLMAP wrote; several are named.
TEST(ColmapReader, FindsTheModelInAWorkspace) {
  const auto scene = MakeSyntheticScene(SmallScene());
  const auto ws = testing::ScratchDir("workspace");
  std::filesystem::create_directories(ws / "sparse" / "0");
  std::filesystem::create_directories(ws / "images");
  testing::WriteColmapBinary(scene.model, ws / "sparse" / "0");
  EXPECT_EQ(FindColmapModelDir(ws), ws / "sparse" / "0");
  EXPECT_EQ(FindColmapModelDir(ws / "sparse"), ws / "sparse" / "0");
  EXPECT_EQ(FindColmapModelDir(ws / "sparse" / "0"), ws / "sparse" / "0");
  std::filesystem::create_directories(ws / "sparse" / "10");
  testing::WriteColmapText(scene.model, ws / "sparse" / "10");
  std::filesystem::create_directories(ws / "sparse" / "2");  // empty: not a model
  const std::string msg = cinepath::testing::InputErrorMessage([&] { FindColmapModelDir(ws); });
  EXPECT_NE(msg.find("holds 2 COLMAP models (" + (ws / "sparse" / "0").string() + ", " +
                     (ws / "sparse" / "10").string() + "): give the one to use as `colmap_dir`"),
            std::string::npos)
      << msg;
  const auto empty = testing::ScratchDir("empty_workspace");
  EXPECT_NE(cinepath::testing::InputErrorMessage([&] {
              FindColmapModelDir(empty);
            }).find("or in sparse/0 as COLMAP writes them"),
            std::string::npos);
}

TEST(ColmapReader, EveryTruncationOfBinaryFilesIsAnInputErrorWithAByteOffset) {
  const auto scene = MakeSyntheticScene(SmallScene());
  const std::string files[3] = {testing::ColmapCamerasBinary(scene.model), testing::ColmapImagesBinary(scene.model),
                                testing::ColmapPoints3DBinary(scene.model)};
  for (int f = 0; f < 3; ++f) {
    const std::string& data = files[f];
    // Every prefix for the small files, a stride for the big one.
    const size_t stride = data.size() > 4000 ? 7 : 1;
    for (size_t len = 0; len < data.size(); len += stride) {
      ColmapModel m;
      const std::string_view cut(data.data(), len);
      const std::string msg = cinepath::testing::InputErrorMessage([&] {
        if (f == 0) ParseColmapCamerasBinary(cut, "x.bin", m);
        if (f == 1) ParseColmapImagesBinary(cut, "x.bin", m);
        if (f == 2) ParseColmapPoints3DBinary(cut, "x.bin", m);
      });
      ASSERT_NE(msg.find("x.bin: byte "), std::string::npos) << "file " << f << " length " << len << ": " << msg;
    }
    // Trailing garbage too.
    ColmapModel m;
    const std::string longer = data + "x";
    const std::string msg = cinepath::testing::InputErrorMessage([&] {
      if (f == 0) ParseColmapCamerasBinary(longer, "x.bin", m);
      if (f == 1) ParseColmapImagesBinary(longer, "x.bin", m);
      if (f == 2) ParseColmapPoints3DBinary(longer, "x.bin", m);
    });
    EXPECT_NE(msg.find("trailing"), std::string::npos) << msg;
  }
}

TEST(ColmapReader, UnknownCameraModelIdIsRejectedWithItsOffset) {
  ColmapModel m;
  m.cameras[3] = {3, 4, 1600, 900, {1, 1, 1, 1, 0, 0, 0, 0}};
  std::string data = testing::ColmapCamerasBinary(m);
  const int32_t eleven = 11;  // RAD_TAN_THIN_PRISM_FISHEYE in newer COLMAP
  std::memcpy(&data[12], &eleven, 4);
  ColmapModel out;
  const std::string msg =
      cinepath::testing::InputErrorMessage([&] { ParseColmapCamerasBinary(data, "cameras.bin", out); });
  EXPECT_NE(msg.find("cameras.bin: byte 12: unknown camera model id 11"), std::string::npos) << msg;

  const std::string text_msg = cinepath::testing::InputErrorMessage(
      [&] { ParseColmapCamerasText("# header\n1 RAD_TAN_THIN_PRISM_FISHEYE 10 10 1 2 3\n", "cameras.txt", out); });
  EXPECT_NE(text_msg.find("cameras.txt: line 2: unknown camera model 'RAD_TAN_THIN_PRISM_FISHEYE'"), std::string::npos)
      << text_msg;
}

TEST(ColmapReader, TextErrorsNameTheLine) {
  ColmapModel m;
  auto msg =
      cinepath::testing::InputErrorMessage([&] { ParseColmapCamerasText("1 PINHOLE 100 100 50 50 50\n", "c.txt", m); });
  EXPECT_NE(msg.find("c.txt: line 1: PINHOLE takes 4 parameters, found 3"), std::string::npos) << msg;
  msg = cinepath::testing::InputErrorMessage(
      [&] { ParseColmapCamerasText("\n\n1 PINHOLE 100 100 50 nan 50 50\n", "c.txt", m); });
  EXPECT_NE(msg.find("c.txt: line 3: camera parameter is not finite"), std::string::npos) << msg;
  msg = cinepath::testing::InputErrorMessage(
      [&] { ParseColmapPoints3DText("#\n7 1 2 inf 1 2 3 0.5 1 0 2 0\n", "p.txt", m); });
  EXPECT_NE(msg.find("p.txt: line 2: Z is not finite"), std::string::npos) << msg;
  msg = cinepath::testing::InputErrorMessage(
      [&] { ParseColmapPoints3DText("7 1 2 3 1 2 300 0.5 1 0 2 0\n", "p.txt", m); });
  EXPECT_NE(msg.find("p.txt: line 1: B: '300' is not a valid integer"), std::string::npos) << msg;
  msg = cinepath::testing::InputErrorMessage([&] { ParseColmapImagesText("1 0 0 0 0 0 0 0 1 a.jpg\n\n", "i.txt", m); });
  EXPECT_NE(msg.find("i.txt: line 1: zero-length quaternion"), std::string::npos) << msg;
  msg = cinepath::testing::InputErrorMessage(
      [&] { ParseColmapImagesText("1 1 0 0 0 0 0 0 1 a.jpg\n1.5 2.5\n", "i.txt", m); });
  EXPECT_NE(msg.find("i.txt: line 2: POINTS2D must be triples"), std::string::npos) << msg;
}

TEST(ColmapReader, BinaryNanIsRejectedWithItsOffset) {
  const auto scene = MakeSyntheticScene(SmallScene());
  std::string data = testing::ColmapPoints3DBinary(scene.model);
  const double nan = std::nan("");
  std::memcpy(&data[8 + 8 + 8], &nan, 8);  // y of the first point
  ColmapModel m;
  const std::string msg =
      cinepath::testing::InputErrorMessage([&] { ParseColmapPoints3DBinary(data, "points3D.bin", m); });
  EXPECT_NE(msg.find("points3D.bin: byte 24: point coordinate is not finite"), std::string::npos) << msg;
}

TEST(ColmapReader, DanglingIdsNameTheReferringElement) {
  auto scene = MakeSyntheticScene(SmallScene());
  // An image whose camera does not exist.
  {
    auto model = scene.model;
    model.images.at(2).camera_id = 9;
    const auto dir = testing::ScratchDir("dangling_camera");
    testing::WriteColmapText(model, dir);
    const std::string msg = cinepath::testing::InputErrorMessage([&] { ReadColmapModel(dir); });
    EXPECT_NE(msg.find("images.txt: line 4: image 2 refers to camera_id 9"), std::string::npos) << msg;
  }
  // A track element naming a keypoint index past the image's keypoints.
  {
    auto model = scene.model;
    auto& point = model.points3d.begin()->second;
    point.track[0].point2d_idx = 100000;
    const auto dir = testing::ScratchDir("dangling_track");
    testing::WriteColmapBinary(model, dir);
    const std::string msg = cinepath::testing::InputErrorMessage([&] { ReadColmapModel(dir); });
    EXPECT_NE(msg.find("points3D.bin: byte 8: point3D 1 track refers to keypoint 100000"), std::string::npos) << msg;
  }
  // A keypoint naming a missing 3D point.
  {
    auto model = scene.model;
    model.points3d.erase(model.points3d.begin());
    const auto dir = testing::ScratchDir("dangling_point");
    testing::WriteColmapBinary(model, dir);
    const std::string msg = cinepath::testing::InputErrorMessage([&] { ReadColmapModel(dir); });
    EXPECT_NE(msg.find("refers to point3D_id 1, which is not in the points3D file"), std::string::npos) << msg;
  }
}

// The six-image Brighton subset (tests/data/photogrammetry), its text form written by COLMAP's own
// model_converter: both forms read to the same model.
TEST(ColmapReader, BrightonBeachTextAndBinaryAreIdentical) {
  const auto base = testing::TestDataDir() / "photogrammetry" / "brighton6_colmap";
  const ColmapModel binary = ReadColmapModel(base / "sparse");
  const ColmapModel text = ReadColmapModel(base / "sparse_txt");
  EXPECT_EQ(binary.images.size(), 6u);
  EXPECT_EQ(binary.points3d.size(), 1056u);
  EXPECT_EQ(binary.cameras.at(1).model_id, static_cast<int>(CameraModelId::kOpenCv));
  EXPECT_NEAR(binary.cameras.at(1).params[0], 1202.08, 0.01);
  EXPECT_TRUE(binary == text);
}

}  // namespace
}  // namespace cinepath::photogrammetry
