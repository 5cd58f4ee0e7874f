#include "core/file_io.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/depfile.h"
#include "core/error.h"
#include "core/progress.h"

namespace cinepath {
namespace {
namespace fs = std::filesystem;

class FileIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cinepath_file_io_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  size_t CountEntries() const {
    return static_cast<size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
  fs::path dir_;
};

TEST_F(FileIoTest, AtomicWriteReplacesAndLeavesNoTemporaries) {
  const fs::path target = dir_ / "out.json";
  WriteFileAtomic(target, "old");
  WriteFileAtomic(target, "new contents");
  EXPECT_EQ(ReadFileToString(target), "new contents");
  EXPECT_EQ(CountEntries(), 1u);
}

TEST_F(FileIoTest, FailedRunLeavesNothing) {
  {
    AtomicOutputs out;
    out.Add(dir_ / "a.glb", "aaa");
    out.Add(dir_ / "b.json", "bbb");
    // No Commit(): the run "failed" before the outputs were complete.
  }
  EXPECT_EQ(CountEntries(), 0u);
}

TEST_F(FileIoTest, CommitLandsAllOutputs) {
  AtomicOutputs out;
  out.Add(dir_ / "a.glb", "aaa");
  out.Add(dir_ / "b.json", "bbb");
  out.Commit();
  EXPECT_EQ(ReadFileToString(dir_ / "a.glb"), "aaa");
  EXPECT_EQ(ReadFileToString(dir_ / "b.json"), "bbb");
  EXPECT_EQ(CountEntries(), 2u);
}

// Read in blocks: a file of several blocks and a partial last one, every byte value, comes back whole.
TEST_F(FileIoTest, ReadsEveryByteOfAFileLargerThanABlock) {
  std::string bytes;
  for (size_t i = 0; i < 200'003; ++i) bytes.push_back(static_cast<char>((i * 7 + i / 256) % 256));
  WriteFileAtomic(dir_ / "big.bin", bytes);
  EXPECT_EQ(ReadFileToString(dir_ / "big.bin"), bytes);
  WriteFileAtomic(dir_ / "empty.bin", "");
  EXPECT_EQ(ReadFileToString(dir_ / "empty.bin"), "");
}

TEST_F(FileIoTest, ErrorsNameTheFile) {
  try {
    ReadFileToString(dir_ / "missing.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.json"), std::string::npos);
  }
  EXPECT_THROW(WriteFileAtomic(dir_ / "no" / "such" / "folder.json", "x"), RuntimeError);
}

TEST(Depfile, EscapesAndDeduplicates) {
  EXPECT_EQ(FormatDepfile({"out/plan.json"}, {"shots.json", "my scene.json", "shots.json", "a$b"}),
            "out/plan.json: shots.json my\\ scene.json a$$b\n");
}

TEST(Progress, NeverDrawsWhenDisabledAndParsesModes) {
  EXPECT_EQ(ParseProgressMode("never"), ProgressMode::kNever);
  EXPECT_EQ(ParseProgressMode("always"), ProgressMode::kAlways);
  EXPECT_THROW(ParseProgressMode("sometimes"), InputError);
  Progress p("test", 10, ProgressMode::kNever);
  EXPECT_FALSE(p.enabled());
  testing::internal::CaptureStderr();
  p.Update(5);
  p.Finish();
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace cinepath
