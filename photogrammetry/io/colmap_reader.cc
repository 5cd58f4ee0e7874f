#include "photogrammetry/io/colmap_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <system_error>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/file_io.h"
#include "core/text_tokens.h"
#include "photogrammetry/georef/camera_models.h"

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Binary: little-endian, read through a bounds-checked cursor that knows its byte offset.

class BinaryCursor {
 public:
  BinaryCursor(std::string_view data, const std::string& source) : data_(data), source_(source) {}

  size_t offset() const { return offset_; }
  size_t remaining() const { return data_.size() - offset_; }
  std::string Where(size_t at) const { return source_ + ": byte " + std::to_string(at); }
  std::string Where() const { return Where(offset_); }

  [[noreturn]] void Fail(size_t at, const std::string& what) const { throw InputError(Located(Where(at), what)); }

  template <typename T>
  T Read(const char* what) {
    if (remaining() < sizeof(T)) {
      Fail(offset_, std::string("truncated: ") + what + " needs " + std::to_string(sizeof(T)) + " bytes, " +
                        std::to_string(remaining()) + " left");
    }
    T value;
    std::memcpy(&value, data_.data() + offset_, sizeof(T));  // host is little-endian (x86-64, arm64)
    offset_ += sizeof(T);
    return value;
  }

  double ReadFinite(const char* what) {
    const size_t at = offset_;
    const double v = Read<double>(what);
    if (!std::isfinite(v)) Fail(at, std::string(what) + " is not finite (" + std::to_string(v) + ")");
    return v;
  }

  std::string ReadCString(const char* what) {
    const size_t at = offset_;
    const void* end = std::memchr(data_.data() + offset_, '\0', remaining());
    if (end == nullptr) Fail(at, std::string("truncated: ") + what + " has no terminating NUL byte");
    const size_t len = static_cast<const char*>(end) - (data_.data() + offset_);
    std::string s(data_.data() + offset_, len);
    offset_ += len + 1;
    return s;
  }

  // Rejects a count that cannot fit in the rest of the file (`min_bytes_each` per element), before
  // anything is allocated for it.
  void CheckCount(uint64_t count, size_t min_bytes_each, size_t count_at, const char* what) const {
    if (min_bytes_each > 0 && count > remaining() / min_bytes_each) {
      Fail(count_at, std::string("truncated or corrupt: ") + what + " = " + std::to_string(count) + " needs at least " +
                         std::to_string(min_bytes_each) + " bytes each, " + std::to_string(remaining()) + " left");
    }
  }

  void ExpectEnd() const {
    if (remaining() != 0) {
      Fail(offset_, std::to_string(remaining()) + " unexpected trailing bytes after the last record");
    }
  }

 private:
  std::string_view data_;
  const std::string& source_;
  size_t offset_ = 0;
};

Eigen::Quaterniond NormalizedQuaternion(double w, double x, double y, double z, bool* ok) {
  Eigen::Quaterniond q(w, x, y, z);
  const double n = q.norm();
  *ok = std::isfinite(n) && n > 1e-12;
  if (*ok) q.normalize();
  return q;
}

// ---------------------------------------------------------------------------------------------
// Text: line by line, whitespace-separated tokens, '#' comment lines.

class TextLine {
 public:
  TextLine(std::string_view line, const std::string& source, size_t line_number)
      : source_(source), line_number_(line_number) {
    tokens_ = WhitespaceTokens(line);
    line_ = line;
  }

  size_t size() const { return tokens_.size(); }
  std::string_view token(size_t i) const { return tokens_[i]; }
  std::string Where() const { return source_ + ": line " + std::to_string(line_number_); }
  [[noreturn]] void Fail(const std::string& what) const { throw InputError(Located(Where(), what)); }

  void Require(size_t index, const char* what) const {
    if (index >= tokens_.size()) Fail(std::string("missing ") + what);
  }

  template <typename Int>
  Int Integer(size_t index, const char* what) const {
    Require(index, what);
    const std::string_view t = tokens_[index];
    Int value{};
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec != std::errc() || ptr != t.data() + t.size()) {
      Fail(std::string(what) + ": '" + std::string(t) + "' is not a valid integer");
    }
    return value;
  }

  double Finite(size_t index, const char* what) const {
    Require(index, what);
    const std::string_view t = tokens_[index];
    double value = 0;
    const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec != std::errc() || ptr != t.data() + t.size()) {
      Fail(std::string(what) + ": '" + std::string(t) + "' is not a number");
    }
    if (!std::isfinite(value)) Fail(std::string(what) + " is not finite ('" + std::string(t) + "')");
    return value;
  }

  // Everything from token `index` to the end of the line, trailing whitespace removed.
  std::string Rest(size_t index, const char* what) const {
    Require(index, what);
    const size_t start = tokens_[index].data() - line_.data();
    std::string_view rest = line_.substr(start);
    while (!rest.empty() && IsTokenSpace(rest.back())) rest.remove_suffix(1);
    return std::string(rest);
  }

 private:
  std::vector<std::string_view> tokens_;
  std::string_view line_;
  const std::string& source_;
  size_t line_number_;
};

// Splits `data` into lines (\n, tolerating \r\n) and hands them out with 1-based numbers.
class LineReader {
 public:
  explicit LineReader(std::string_view data) : data_(data) {}
  bool Next(std::string_view* line, size_t* number) {
    if (pos_ >= data_.size()) return false;
    size_t end = data_.find('\n', pos_);
    if (end == std::string_view::npos) end = data_.size();
    *line = data_.substr(pos_, end - pos_);
    pos_ = end + 1;
    *number = ++line_number_;
    return true;
  }

 private:
  std::string_view data_;
  size_t pos_ = 0;
  size_t line_number_ = 0;
};

bool IsBlankOrComment(std::string_view line) {
  for (char c : line) {
    if (IsTokenSpace(c)) continue;
    return c == '#';
  }
  return true;
}

void CheckCamera(const ColmapCamera& camera, const std::function<void(const std::string&)>& fail) {
  if (camera.width_px == 0 || camera.height_px == 0) fail("camera width and height must be > 0");
}

}  // namespace

// ---------------------------------------------------------------------------------------------

void ParseColmapCamerasBinary(std::string_view data, const std::string& source, ColmapModel& model) {
  BinaryCursor in(data, source);
  const size_t count_at = in.offset();
  const uint64_t num_cameras = in.Read<uint64_t>("number of cameras");
  in.CheckCount(num_cameras, 4 + 4 + 8 + 8, count_at, "number of cameras");
  for (uint64_t i = 0; i < num_cameras; ++i) {
    const size_t at = in.offset();
    ColmapCamera camera;
    camera.camera_id = in.Read<uint32_t>("camera_id");
    const size_t model_at = in.offset();
    camera.model_id = in.Read<int32_t>("model_id");
    if (!IsKnownCameraModel(camera.model_id)) {
      in.Fail(model_at, "unknown camera model id " + std::to_string(camera.model_id) + " (COLMAP 3.8 defines 0..10)");
    }
    camera.width_px = in.Read<uint64_t>("width");
    camera.height_px = in.Read<uint64_t>("height");
    CheckCamera(camera, [&](const std::string& what) { in.Fail(at, what); });
    const int n = CameraModelNumParams(camera.model_id);
    camera.params.resize(n);
    for (int k = 0; k < n; ++k) camera.params[k] = in.ReadFinite("camera parameter");
    if (!model.cameras.emplace(camera.camera_id, camera).second) {
      in.Fail(at, "duplicate camera_id " + std::to_string(camera.camera_id));
    }
  }
  in.ExpectEnd();
}

void ParseColmapImagesBinary(std::string_view data, const std::string& source, ColmapModel& model,
                             ColmapLocations* where) {
  BinaryCursor in(data, source);
  const size_t count_at = in.offset();
  const uint64_t num_images = in.Read<uint64_t>("number of images");
  in.CheckCount(num_images, 4 + 7 * 8 + 4 + 1 + 8, count_at, "number of images");
  for (uint64_t i = 0; i < num_images; ++i) {
    const size_t at = in.offset();
    ColmapImage image;
    image.image_id = in.Read<uint32_t>("image_id");
    double q[4];
    for (double& c : q) c = in.ReadFinite("quaternion component");
    bool ok = false;
    image.cam_from_world_rotation = NormalizedQuaternion(q[0], q[1], q[2], q[3], &ok);
    if (!ok) in.Fail(at, "image " + std::to_string(image.image_id) + ": zero-length quaternion");
    for (int k = 0; k < 3; ++k) image.cam_from_world_translation[k] = in.ReadFinite("translation");
    image.camera_id = in.Read<uint32_t>("camera_id");
    image.name = in.ReadCString("image name");
    if (image.name.empty()) in.Fail(at, "image " + std::to_string(image.image_id) + ": empty name");
    const size_t n_at = in.offset();
    const uint64_t num_points2d = in.Read<uint64_t>("number of points2D");
    in.CheckCount(num_points2d, 8 + 8 + 8, n_at, "number of points2D");
    image.points2d_px.resize(num_points2d);
    image.point3d_ids.resize(num_points2d);
    for (uint64_t k = 0; k < num_points2d; ++k) {
      image.points2d_px[k].x() = in.ReadFinite("point2D x");
      image.points2d_px[k].y() = in.ReadFinite("point2D y");
      image.point3d_ids[k] = in.Read<uint64_t>("point3D_id");
    }
    const uint32_t id = image.image_id;
    if (!model.images.emplace(id, std::move(image)).second) {
      in.Fail(at, "duplicate image_id " + std::to_string(id));
    }
    if (where) where->images[id] = in.Where(at);
  }
  in.ExpectEnd();
}

void ParseColmapPoints3DBinary(std::string_view data, const std::string& source, ColmapModel& model,
                               ColmapLocations* where) {
  BinaryCursor in(data, source);
  const size_t count_at = in.offset();
  const uint64_t num_points = in.Read<uint64_t>("number of points3D");
  in.CheckCount(num_points, 8 + 3 * 8 + 3 + 8 + 8, count_at, "number of points3D");
  for (uint64_t i = 0; i < num_points; ++i) {
    const size_t at = in.offset();
    ColmapPoint3D point;
    point.point3d_id = in.Read<uint64_t>("point3D_id");
    if (point.point3d_id == kInvalidPoint3DId) in.Fail(at, "point3D_id 2^64-1 is COLMAP's 'no point'");
    for (int k = 0; k < 3; ++k) point.xyz[k] = in.ReadFinite("point coordinate");
    for (int k = 0; k < 3; ++k) point.rgb[k] = in.Read<uint8_t>("colour");
    point.error_px = in.ReadFinite("reprojection error");
    const size_t n_at = in.offset();
    const uint64_t track_length = in.Read<uint64_t>("track length");
    in.CheckCount(track_length, 8, n_at, "track length");
    point.track.resize(track_length);
    for (auto& element : point.track) {
      element.image_id = in.Read<uint32_t>("track image_id");
      element.point2d_idx = in.Read<uint32_t>("track point2D_idx");
    }
    const uint64_t id = point.point3d_id;
    if (!model.points3d.emplace(id, std::move(point)).second) {
      in.Fail(at, "duplicate point3D_id " + std::to_string(id));
    }
    if (where) where->points3d[id] = in.Where(at);
  }
  in.ExpectEnd();
}

// ---------------------------------------------------------------------------------------------

void ParseColmapCamerasText(std::string_view data, const std::string& source, ColmapModel& model) {
  LineReader lines(data);
  std::string_view raw;
  size_t number;
  while (lines.Next(&raw, &number)) {
    if (IsBlankOrComment(raw)) continue;
    const TextLine line(raw, source, number);
    ColmapCamera camera;
    camera.camera_id = line.Integer<uint32_t>(0, "CAMERA_ID");
    line.Require(1, "MODEL");
    const auto model_id = CameraModelIdFromName(line.token(1));
    if (!model_id) {
      // Also accept a numeric id, as some exporters write it; still reject unknown ones.
      int numeric = -1;
      const std::string_view t = line.token(1);
      const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), numeric);
      if (ec != std::errc() || ptr != t.data() + t.size() || !IsKnownCameraModel(numeric)) {
        line.Fail("unknown camera model '" + std::string(t) +
                  "' (COLMAP 3.8 defines SIMPLE_PINHOLE, "
                  "PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, OPENCV_FISHEYE, FULL_OPENCV, FOV, "
                  "SIMPLE_RADIAL_FISHEYE, RADIAL_FISHEYE, THIN_PRISM_FISHEYE)");
      }
      camera.model_id = numeric;
    } else {
      camera.model_id = *model_id;
    }
    camera.width_px = line.Integer<uint64_t>(2, "WIDTH");
    camera.height_px = line.Integer<uint64_t>(3, "HEIGHT");
    CheckCamera(camera, [&](const std::string& what) { line.Fail(what); });
    const size_t n = CameraModelNumParams(camera.model_id);
    if (line.size() != 4 + n) {
      line.Fail(std::string(CameraModelName(camera.model_id)) + " takes " + std::to_string(n) + " parameters, found " +
                std::to_string(line.size() < 4 ? 0 : line.size() - 4));
    }
    for (size_t k = 0; k < n; ++k) camera.params.push_back(line.Finite(4 + k, "camera parameter"));
    if (!model.cameras.emplace(camera.camera_id, camera).second) {
      line.Fail("duplicate CAMERA_ID " + std::to_string(camera.camera_id));
    }
  }
}

void ParseColmapImagesText(std::string_view data, const std::string& source, ColmapModel& model,
                           ColmapLocations* where) {
  LineReader lines(data);
  std::string_view raw;
  size_t number;
  while (lines.Next(&raw, &number)) {
    if (IsBlankOrComment(raw)) continue;
    const TextLine line(raw, source, number);
    ColmapImage image;
    image.image_id = line.Integer<uint32_t>(0, "IMAGE_ID");
    bool ok = false;
    image.cam_from_world_rotation = NormalizedQuaternion(line.Finite(1, "QW"), line.Finite(2, "QX"),
                                                         line.Finite(3, "QY"), line.Finite(4, "QZ"), &ok);
    if (!ok) line.Fail("zero-length quaternion");
    image.cam_from_world_translation = {line.Finite(5, "TX"), line.Finite(6, "TY"), line.Finite(7, "TZ")};
    image.camera_id = line.Integer<uint32_t>(8, "CAMERA_ID");
    image.name = line.Rest(9, "NAME");
    // The keypoint line follows immediately (it may be empty; at the end of the file it may be absent).
    std::string_view points_raw;
    size_t points_number;
    if (lines.Next(&points_raw, &points_number)) {
      const TextLine points(points_raw, source, points_number);
      if (points.size() % 3 != 0) {
        points.Fail("POINTS2D must be triples (X, Y, POINT3D_ID), found " + std::to_string(points.size()) + " values");
      }
      const size_t n = points.size() / 3;
      image.points2d_px.resize(n);
      image.point3d_ids.resize(n);
      for (size_t k = 0; k < n; ++k) {
        image.points2d_px[k] = {points.Finite(3 * k, "point2D X"), points.Finite(3 * k + 1, "point2D Y")};
        if (points.token(3 * k + 2) == "-1") {
          image.point3d_ids[k] = kInvalidPoint3DId;
        } else {
          image.point3d_ids[k] = points.Integer<uint64_t>(3 * k + 2, "POINT3D_ID");
        }
      }
    }
    const uint32_t id = image.image_id;
    if (!model.images.emplace(id, std::move(image)).second) {
      line.Fail("duplicate IMAGE_ID " + std::to_string(id));
    }
    if (where) where->images[id] = line.Where();
  }
}

void ParseColmapPoints3DText(std::string_view data, const std::string& source, ColmapModel& model,
                             ColmapLocations* where) {
  LineReader lines(data);
  std::string_view raw;
  size_t number;
  while (lines.Next(&raw, &number)) {
    if (IsBlankOrComment(raw)) continue;
    const TextLine line(raw, source, number);
    ColmapPoint3D point;
    point.point3d_id = line.Integer<uint64_t>(0, "POINT3D_ID");
    if (point.point3d_id == kInvalidPoint3DId) line.Fail("POINT3D_ID 2^64-1 is COLMAP's 'no point'");
    point.xyz = {line.Finite(1, "X"), line.Finite(2, "Y"), line.Finite(3, "Z")};
    point.rgb = {line.Integer<uint8_t>(4, "R"), line.Integer<uint8_t>(5, "G"), line.Integer<uint8_t>(6, "B")};
    point.error_px = line.Finite(7, "ERROR");
    if ((line.size() - 8) % 2 != 0) line.Fail("TRACK must be pairs (IMAGE_ID, POINT2D_IDX)");
    for (size_t k = 8; k + 1 < line.size(); k += 2) {
      point.track.push_back(
          {line.Integer<uint32_t>(k, "track IMAGE_ID"), line.Integer<uint32_t>(k + 1, "track POINT2D_IDX")});
    }
    const uint64_t id = point.point3d_id;
    if (!model.points3d.emplace(id, std::move(point)).second) {
      line.Fail("duplicate POINT3D_ID " + std::to_string(id));
    }
    if (where) where->points3d[id] = line.Where();
  }
}

// ---------------------------------------------------------------------------------------------

void ValidateColmapModel(const ColmapModel& model, const ColmapLocations& where) {
  auto image_where = [&](uint32_t id) {
    const auto it = where.images.find(id);
    return it == where.images.end() ? "image " + std::to_string(id) : it->second;
  };
  auto point_where = [&](uint64_t id) {
    const auto it = where.points3d.find(id);
    return it == where.points3d.end() ? "point3D " + std::to_string(id) : it->second;
  };
  for (const auto& [id, image] : model.images) {
    if (!model.cameras.contains(image.camera_id)) {
      throw InputError(Located(image_where(id), "image " + std::to_string(id) + " refers to camera_id " +
                                                    std::to_string(image.camera_id) +
                                                    ", which is not in the cameras file"));
    }
    for (size_t k = 0; k < image.point3d_ids.size(); ++k) {
      const uint64_t pid = image.point3d_ids[k];
      if (pid != kInvalidPoint3DId && !model.points3d.contains(pid)) {
        throw InputError(Located(image_where(id), "image " + std::to_string(id) + " keypoint " + std::to_string(k) +
                                                      " refers to point3D_id " + std::to_string(pid) +
                                                      ", which is not in the points3D file"));
      }
    }
  }
  for (const auto& [id, point] : model.points3d) {
    for (const auto& element : point.track) {
      const auto it = model.images.find(element.image_id);
      if (it == model.images.end()) {
        throw InputError(Located(point_where(id), "point3D " + std::to_string(id) + " track refers to image_id " +
                                                      std::to_string(element.image_id) +
                                                      ", which is not in the images file"));
      }
      if (element.point2d_idx >= it->second.points2d_px.size()) {
        throw InputError(Located(point_where(id), "point3D " + std::to_string(id) + " track refers to keypoint " +
                                                      std::to_string(element.point2d_idx) + " of image " +
                                                      std::to_string(element.image_id) + ", which has " +
                                                      std::to_string(it->second.points2d_px.size())));
      }
    }
  }
}

ColmapFormat DetectColmapFormat(const fs::path& dir) {
  auto all_exist = [&](const char* ext) {
    for (const char* stem : {"cameras", "images", "points3D"}) {
      if (!fs::is_regular_file(dir / (std::string(stem) + ext))) return false;
    }
    return true;
  };
  if (all_exist(".bin")) return ColmapFormat::kBinary;
  if (all_exist(".txt")) return ColmapFormat::kText;
  if (!fs::is_directory(dir)) throw InputError(Located(dir.string(), "not a directory"));
  throw InputError(Located(dir.string(),
                           "not a COLMAP sparse model: needs cameras, images and points3D "
                           "as .bin or .txt"));
}

namespace {

bool HoldsColmapModel(const fs::path& dir) {
  for (const char* ext : {".bin", ".txt"}) {
    bool all = true;
    for (const char* stem : {"cameras", "images", "points3D"})
      all = all && fs::is_regular_file(dir / (std::string(stem) + ext));
    if (all) return true;
  }
  return false;
}

bool IsNumber(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

fs::path FindColmapModelDir(const fs::path& dir) {
  if (HoldsColmapModel(dir) || !fs::is_directory(dir)) return dir;  // DetectColmapFormat says what is wrong
  std::vector<fs::path> found;
  for (const fs::path& parent : {dir / "sparse", dir}) {
    if (!fs::is_directory(parent)) continue;
    std::vector<std::pair<long long, fs::path>> numbered;
    for (const auto& entry : fs::directory_iterator(parent)) {
      const std::string name = entry.path().filename().string();
      if (entry.is_directory() && IsNumber(name) && name.size() < 10 && HoldsColmapModel(entry.path())) {
        numbered.emplace_back(std::stoll(name), (parent / name).lexically_normal());
      }
    }
    std::sort(numbered.begin(), numbered.end());
    for (const auto& [n, path] : numbered) found.push_back(path);
  }
  if (HoldsColmapModel(dir / "sparse")) found.push_back((dir / "sparse").lexically_normal());
  if (found.empty()) {
    throw InputError(Located(dir.string(),
                             "not a COLMAP sparse model: needs cameras, images and points3D as .bin or "
                             ".txt (here, or in sparse/0 as COLMAP writes them)"));
  }
  if (found.size() > 1) {
    std::string names;
    for (const fs::path& f : found) names += (names.empty() ? "" : ", ") + f.string();
    throw InputError(Located(dir.string(), "holds " + std::to_string(found.size()) + " COLMAP models (" + names +
                                               "): give the one to use as `colmap_dir`"));
  }
  return found.front();
}

ColmapModel ReadColmapModel(const fs::path& dir) { return ReadColmapModel(dir, DetectColmapFormat(dir)); }

ColmapModel ReadColmapModel(const fs::path& dir, ColmapFormat format) {
  ColmapModel model;
  ColmapLocations where;
  auto name = [&](const char* file) { return (dir / file).string(); };
  if (format == ColmapFormat::kBinary) {
    ParseColmapCamerasBinary(ReadFileToString(dir / "cameras.bin"), name("cameras.bin"), model);
    ParseColmapImagesBinary(ReadFileToString(dir / "images.bin"), name("images.bin"), model, &where);
    ParseColmapPoints3DBinary(ReadFileToString(dir / "points3D.bin"), name("points3D.bin"), model, &where);
  } else {
    ParseColmapCamerasText(ReadFileToString(dir / "cameras.txt"), name("cameras.txt"), model);
    ParseColmapImagesText(ReadFileToString(dir / "images.txt"), name("images.txt"), model, &where);
    ParseColmapPoints3DText(ReadFileToString(dir / "points3D.txt"), name("points3D.txt"), model, &where);
  }
  ValidateColmapModel(model, where);
  return model;
}

}  // namespace cinepath::photogrammetry
