#include "photogrammetry/io/colmap_database.h"

#include <sqlite3.h>

#include <cstring>
#include <map>
#include <memory>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;

struct CloseDatabase {
  void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct FinalizeStatement {
  void operator()(sqlite3_stmt* s) const { sqlite3_finalize(s); }
};
using Database = std::unique_ptr<sqlite3, CloseDatabase>;
using Statement = std::unique_ptr<sqlite3_stmt, FinalizeStatement>;

Statement Prepare(sqlite3* db, const std::string& where, const std::string& sql) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &raw, nullptr) != SQLITE_OK) {
    throw InputError(Located(where, std::string("not a COLMAP database (") + sqlite3_errmsg(db) + ")"));
  }
  return Statement(raw);
}

// Runs `sql` and calls `row` on each result row; InputError on a read error (a corrupt file).
template <typename Row>
void ForEachRow(sqlite3* db, const std::string& where, const std::string& sql, Row&& row) {
  Statement statement = Prepare(db, where, sql);
  for (;;) {
    const int rc = sqlite3_step(statement.get());
    if (rc == SQLITE_DONE) return;
    if (rc != SQLITE_ROW) throw InputError(Located(where, std::string("cannot be read (") + sqlite3_errmsg(db) + ")"));
    row(statement.get());
  }
}

// The blob of a (image_id, rows, cols, data) row, checked against rows × cols × element_bytes.
const void* CheckedBlob(sqlite3_stmt* s, const std::string& where, std::int64_t rows, std::int64_t cols,
                        std::size_t element_bytes) {
  const std::int64_t bytes = sqlite3_column_bytes(s, 3);
  if (rows < 0 || cols < 0 || rows * cols * static_cast<std::int64_t>(element_bytes) != bytes) {
    throw InputError(Located(where, std::to_string(bytes) + " bytes of data for " + std::to_string(rows) + " rows × " +
                                        std::to_string(cols) + " columns"));
  }
  return sqlite3_column_blob(s, 3);
}

}  // namespace

std::vector<ColmapImageFeatures> ReadColmapFeatures(const fs::path& database) {
  const std::string file = database.string();
  if (!fs::is_regular_file(database)) throw InputError(Located(file, "no such file (COLMAP database)"));
  sqlite3* raw = nullptr;
  const int rc = sqlite3_open_v2(file.c_str(), &raw, SQLITE_OPEN_READONLY, nullptr);
  Database db(raw);
  if (rc != SQLITE_OK) throw InputError(Located(file, std::string("cannot be opened (") + sqlite3_errmsg(raw) + ")"));

  std::map<std::int64_t, ColmapImageFeatures> images;
  ForEachRow(db.get(), file + ": images",
             "SELECT images.image_id, images.name, cameras.width, cameras.height FROM images LEFT JOIN cameras ON "
             "images.camera_id = cameras.camera_id ORDER BY images.image_id",
             [&](sqlite3_stmt* s) {
               ColmapImageFeatures& image = images[sqlite3_column_int64(s, 0)];
               image.image_id = static_cast<std::uint32_t>(sqlite3_column_int64(s, 0));
               const unsigned char* name = sqlite3_column_text(s, 1);
               image.name = name ? reinterpret_cast<const char*>(name) : "";
               image.width_px = sqlite3_column_int(s, 2);
               image.height_px = sqlite3_column_int(s, 3);
               if (image.width_px <= 0 || image.height_px <= 0) {
                 throw InputError(Located(file + ": images[image_id " + std::to_string(image.image_id) + "]",
                                          "no camera with a width and height"));
               }
             });
  auto image_of = [&](sqlite3_stmt* s, const std::string& table) -> ColmapImageFeatures& {
    const std::int64_t id = sqlite3_column_int64(s, 0);
    auto it = images.find(id);
    if (it == images.end()) {
      throw InputError(Located(file + ": " + table + "[image_id " + std::to_string(id) + "]", "no such image"));
    }
    return it->second;
  };
  ForEachRow(db.get(), file + ": keypoints", "SELECT image_id, rows, cols, data FROM keypoints", [&](sqlite3_stmt* s) {
    ColmapImageFeatures& image = image_of(s, "keypoints");
    const std::string where = file + ": keypoints[image_id " + std::to_string(image.image_id) + "]";
    const std::int64_t rows = sqlite3_column_int64(s, 1), cols = sqlite3_column_int64(s, 2);
    if (rows > 0 && cols != 2 && cols != 4 && cols != 6) {
      throw InputError(Located(where + ".cols", std::to_string(cols) + " (COLMAP stores 2, 4 or 6)"));
    }
    const void* data = CheckedBlob(s, where + ".data", rows, cols, sizeof(float));
    image.keypoint_columns = static_cast<int>(cols);
    image.keypoints.resize(static_cast<std::size_t>(rows * cols));
    if (!image.keypoints.empty()) std::memcpy(image.keypoints.data(), data, image.keypoints.size() * sizeof(float));
  });
  ForEachRow(db.get(), file + ": descriptors", "SELECT image_id, rows, cols, data FROM descriptors",
             [&](sqlite3_stmt* s) {
               ColmapImageFeatures& image = image_of(s, "descriptors");
               const std::string where = file + ": descriptors[image_id " + std::to_string(image.image_id) + "]";
               const std::int64_t rows = sqlite3_column_int64(s, 1), cols = sqlite3_column_int64(s, 2);
               if (rows > 0 && cols != kSiftDescriptorBytes) {
                 throw InputError(Located(where + ".cols", std::to_string(cols) + " (SIFT descriptors have 128)"));
               }
               const void* data = CheckedBlob(s, where + ".data", rows, cols, 1);
               image.descriptors.resize(static_cast<std::size_t>(rows * cols));
               if (!image.descriptors.empty()) std::memcpy(image.descriptors.data(), data, image.descriptors.size());
             });

  std::vector<ColmapImageFeatures> out;
  for (auto& [id, image] : images) {
    const std::size_t keypoint_rows =
        image.keypoint_columns > 0 ? image.keypoints.size() / static_cast<std::size_t>(image.keypoint_columns) : 0;
    if (keypoint_rows != image.num_keypoints()) {
      throw InputError(Located(
          file + ": image_id " + std::to_string(id),
          std::to_string(keypoint_rows) + " keypoints but " + std::to_string(image.num_keypoints()) + " descriptors"));
    }
    out.push_back(std::move(image));
  }
  return out;
}

}  // namespace cinepath::photogrammetry
