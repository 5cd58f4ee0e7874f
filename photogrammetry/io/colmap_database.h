// Reads the features COLMAP's feature_extractor stored in its SQLite database (database.db): every
// image's id and name, its keypoints (x, y, then the affine shape COLMAP keeps) and its SIFT
// descriptors (128 bytes each, one row per keypoint), and the size of its camera's images. The
// database is opened read-only; only the `cameras`, `images`, `keypoints` and `descriptors` tables are
// read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace cinepath::photogrammetry {

inline constexpr int kSiftDescriptorBytes = 128;

struct ColmapImageFeatures {
  std::uint32_t image_id = 0;
  std::string name;  // the image's path relative to COLMAP's image folder
  int width_px = 0;  // its camera's image size
  int height_px = 0;
  int keypoint_columns = 0;               // 2 (x, y), 4 (+ scale, orientation) or 6 (+ affine shape)
  std::vector<float> keypoints;           // num_keypoints() rows of keypoint_columns, in pixels
  std::vector<std::uint8_t> descriptors;  // num_keypoints() rows of kSiftDescriptorBytes
  std::size_t num_keypoints() const { return descriptors.size() / kSiftDescriptorBytes; }
};

// Every image of the database, by ascending image_id. An image without keypoints has none (empty
// vectors). InputError naming the file and the table/field when the file is missing, not a SQLite
// database, lacks a table, or holds a blob whose size does not match its rows and columns.
std::vector<ColmapImageFeatures> ReadColmapFeatures(const std::filesystem::path& database);

}  // namespace cinepath::photogrammetry
