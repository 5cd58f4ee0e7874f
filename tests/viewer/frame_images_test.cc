#include "viewer/frame_images.h"

#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::viewer {
namespace {

TEST(FrameImages, IndexFromRenderNames) {
  EXPECT_EQ(FrameIndexFromFileName("frame_000042.png"), 42);
  EXPECT_EQ(FrameIndexFromFileName("frame_1234567.jpg"), 1234567);
  EXPECT_EQ(FrameIndexFromFileName("frame_42.png"), -1);
  EXPECT_EQ(FrameIndexFromFileName("sheet.png"), -1);
  EXPECT_EQ(FrameIndexFromFileName("frame_00004x.png"), -1);
}

TEST(FrameImages, FindsFramesOfThePlanPreferringPng) {
  const auto dir = std::filesystem::path(testing::TempDir()) / "viewer_frames";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  for (const char* name : {"frame_000000.png", "frame_000002.jpg", "frame_000002.png", "frame_000003.jpg",
                           "frame_000009.png", "sheet.png", "frame_000001.exr"}) {
    std::ofstream(dir / name) << "x";
  }
  const auto frames = FindRenderedFrames(dir, 5);  // samples 0..4
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames.at(0).mime_type, "image/png");
  EXPECT_EQ(frames.at(2).path.filename(), "frame_000002.png");
  EXPECT_EQ(frames.at(3).mime_type, "image/jpeg");
  EXPECT_THROW(FindRenderedFrames(dir / "missing", 5), InputError);
}

}  // namespace
}  // namespace cinepath::viewer
