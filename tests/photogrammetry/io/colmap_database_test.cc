#include "photogrammetry/io/colmap_database.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/command_line.h"
#include "tests/support/input_error.h"

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;
using cinepath::testing::InputErrorMessage;

// The four tables COLMAP 3.8 creates that the reader reads (the same columns, fewer constraints).
const char* kSchema =
    "CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, model INTEGER NOT NULL, "
    "width INTEGER NOT NULL, height INTEGER NOT NULL, params BLOB, prior_focal_length INTEGER NOT NULL);"
    "INSERT INTO cameras VALUES (1, 4, 800, 450, NULL, 0);"
    "CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, name TEXT NOT NULL UNIQUE, "
    "camera_id INTEGER NOT NULL);"
    "CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL, "
    "data BLOB);"
    "CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL, "
    "data BLOB);";

class ColmapDatabaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = cinepath::testing::MakeTempDir("cinepath_colmap_db");
    ASSERT_FALSE(dir_.empty());
    path_ = dir_ / "database.db";
  }
  void TearDown() override { fs::remove_all(dir_); }

  void Exec(const std::string& sql) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
    char* error = nullptr;
    const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
    const std::string message = error ? error : "";
    sqlite3_free(error);
    sqlite3_close(db);
    ASSERT_EQ(rc, SQLITE_OK) << message;
  }

  // Inserts (image_id, rows, cols, data) into `table`, the data as a blob of `bytes`.
  void InsertBlob(const std::string& table, int image_id, int rows, int cols, const void* bytes, int size) {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path_.c_str(), &db), SQLITE_OK);
    sqlite3_stmt* s = nullptr;
    const std::string sql = "INSERT INTO " + table + " VALUES (?, ?, ?, ?)";
    ASSERT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &s, nullptr), SQLITE_OK);
    sqlite3_bind_int(s, 1, image_id);
    sqlite3_bind_int(s, 2, rows);
    sqlite3_bind_int(s, 3, cols);
    sqlite3_bind_blob(s, 4, bytes, size, SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(s), SQLITE_DONE);
    sqlite3_finalize(s);
    sqlite3_close(db);
  }

  // Two images: "b.jpg" (id 2) with three keypoints, "a.jpg" (id 1) with two; keypoints of 6 columns.
  void MakeTwoImages() {
    Exec(kSchema);
    Exec("INSERT INTO images VALUES (2, 'b.jpg', 1); INSERT INTO images VALUES (1, 'a.jpg', 1);");
    for (int id : {1, 2}) {
      const int n = id == 1 ? 2 : 3;
      std::vector<float> keypoints(static_cast<size_t>(n) * 6);
      for (size_t i = 0; i < keypoints.size(); ++i) keypoints[i] = static_cast<float>(id * 100 + i);
      std::vector<unsigned char> descriptors(static_cast<size_t>(n) * 128);
      for (size_t i = 0; i < descriptors.size(); ++i) descriptors[i] = static_cast<unsigned char>((id * 7 + i) % 256);
      InsertBlob("keypoints", id, n, 6, keypoints.data(), static_cast<int>(keypoints.size() * sizeof(float)));
      InsertBlob("descriptors", id, n, 128, descriptors.data(), static_cast<int>(descriptors.size()));
    }
  }

  fs::path dir_;
  fs::path path_;
};

TEST_F(ColmapDatabaseTest, ReadsImagesKeypointsAndDescriptorsByImageId) {
  MakeTwoImages();
  const std::vector<ColmapImageFeatures> images = ReadColmapFeatures(path_);
  ASSERT_EQ(images.size(), 2u);
  EXPECT_EQ(images[0].image_id, 1u);
  EXPECT_EQ(images[0].name, "a.jpg");
  EXPECT_EQ(images[1].name, "b.jpg");
  EXPECT_EQ(images[1].width_px, 800);
  EXPECT_EQ(images[1].height_px, 450);
  EXPECT_EQ(images[0].num_keypoints(), 2u);
  EXPECT_EQ(images[1].num_keypoints(), 3u);
  EXPECT_EQ(images[1].keypoint_columns, 6);
  ASSERT_EQ(images[1].keypoints.size(), 18u);
  EXPECT_EQ(images[1].keypoints[0], 200.0f);
  EXPECT_EQ(images[1].keypoints[17], 217.0f);
  ASSERT_EQ(images[0].descriptors.size(), 256u);
  EXPECT_EQ(images[0].descriptors[0], 7);
  EXPECT_EQ(images[0].descriptors[255], (7 + 255) % 256);
}

TEST_F(ColmapDatabaseTest, AnImageWithoutFeaturesHasNone) {
  Exec(kSchema);
  Exec("INSERT INTO images VALUES (1, 'a.jpg', 1);");
  const std::vector<ColmapImageFeatures> images = ReadColmapFeatures(path_);
  ASSERT_EQ(images.size(), 1u);
  EXPECT_EQ(images[0].num_keypoints(), 0u);
}

TEST_F(ColmapDatabaseTest, AnImageWithoutItsCameraIsNamed) {
  Exec(kSchema);
  Exec("INSERT INTO images VALUES (1, 'a.jpg', 3);");
  const std::string message = InputErrorMessage([&] { ReadColmapFeatures(path_); });
  EXPECT_NE(message.find("images[image_id 1]: no camera with a width and height"), std::string::npos) << message;
}

TEST_F(ColmapDatabaseTest, AMissingFileIsNamed) {
  const std::string message = InputErrorMessage([&] { ReadColmapFeatures(path_); });
  EXPECT_NE(message.find(path_.string()), std::string::npos) << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;
}

TEST_F(ColmapDatabaseTest, ACorruptFileIsAClearError) {
  std::ofstream(path_, std::ios::binary) << std::string(4096, 'x');
  const std::string message = InputErrorMessage([&] { ReadColmapFeatures(path_); });
  EXPECT_NE(message.find(path_.string()), std::string::npos) << message;
  EXPECT_NE(message.find("not a COLMAP database"), std::string::npos) << message;
}

TEST_F(ColmapDatabaseTest, ADatabaseWithoutTheTablesIsNotACOLMAPDatabase) {
  Exec("CREATE TABLE other (x INTEGER);");
  const std::string message = InputErrorMessage([&] { ReadColmapFeatures(path_); });
  EXPECT_NE(message.find(path_.string() + ": images"), std::string::npos) << message;
  EXPECT_NE(message.find("not a COLMAP database"), std::string::npos) << message;
}

TEST_F(ColmapDatabaseTest, ABlobOfTheWrongSizeIsNamed) {
  Exec(kSchema);
  Exec("INSERT INTO images VALUES (1, 'a.jpg', 1);");
  const unsigned char bytes[100] = {};
  InsertBlob("descriptors", 1, 1, 128, bytes, sizeof bytes);
  const std::string message = InputErrorMessage([&] { ReadColmapFeatures(path_); });
  EXPECT_NE(message.find("descriptors[image_id 1].data: 100 bytes of data for 1 rows × 128 columns"), std::string::npos)
      << message;
}

TEST_F(ColmapDatabaseTest, KeypointsAndDescriptorsMustAgree) {
  Exec(kSchema);
  Exec("INSERT INTO images VALUES (1, 'a.jpg', 1);");
  const float keypoints[4] = {1, 2, 3, 4};
  const unsigned char descriptors[128] = {};
  InsertBlob("keypoints", 1, 2, 2, keypoints, sizeof keypoints);
  InsertBlob("descriptors", 1, 1, 128, descriptors, sizeof descriptors);
  const std::string message = InputErrorMessage([&] { ReadColmapFeatures(path_); });
  EXPECT_NE(message.find("image_id 1: 2 keypoints but 1 descriptors"), std::string::npos) << message;
}

TEST_F(ColmapDatabaseTest, FeaturesOfAnUnknownImageAreNamed) {
  Exec(kSchema);
  const unsigned char descriptors[128] = {};
  InsertBlob("descriptors", 5, 1, 128, descriptors, sizeof descriptors);
  const std::string message = InputErrorMessage([&] { ReadColmapFeatures(path_); });
  EXPECT_NE(message.find("descriptors[image_id 5]: no such image"), std::string::npos) << message;
}

}  // namespace
}  // namespace cinepath::photogrammetry
