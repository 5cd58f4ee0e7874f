// Readers for COLMAP 3.8 sparse models, text and binary (file formats: colmap.github.io/format.html,
// and colmap@3.8:src/base/reconstruction.cc).
//
// ReadColmapModel(dir) picks the format as COLMAP does: cameras.bin + images.bin + points3D.bin when
// all three exist, else the three .txt files (binary is preferred when both exist). Newer COLMAP's
// rigs/frames files are ignored (backward compatible).
//
// Every problem is an InputError naming the file and where: "images.bin: byte 4711: ..." for
// binary, "points3D.txt: line 12: ..." for text. Checked: truncation, trailing bytes, unknown camera
// model ids/names, parameter counts, NaN/Inf anywhere, zero quaternions, duplicate ids, and dangling
// references (an image's camera, a keypoint's 3D point, a track's image or keypoint index), with the
// location of the element that refers to the missing id.
//
// The Parse* functions take file contents and a display name, so they can be fuzzed; they validate
// one file on its own. ValidateColmapModel checks the cross-file references.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "photogrammetry/io/colmap_model.h"

namespace cinepath::photogrammetry {

enum class ColmapFormat { kBinary, kText };

// Which format ReadColmapModel would read in `dir`; InputError when neither set is complete.
ColmapFormat DetectColmapFormat(const std::filesystem::path& dir);

// The sparse model a user means by `dir`: `dir` itself when it holds one, else the only model among
// the places COLMAP writes them — `dir`/sparse/<N>, `dir`/<N> (N a number) and `dir`/sparse — so a
// workspace root or its sparse/ folder works too. InputError when there is none, or several (named,
// so the user can pick one).
std::filesystem::path FindColmapModelDir(const std::filesystem::path& dir);

ColmapModel ReadColmapModel(const std::filesystem::path& dir);
ColmapModel ReadColmapModel(const std::filesystem::path& dir, ColmapFormat format);

// Cross-file references. `where` holds, per element, the location string the parsers recorded
// (ColmapLocations); messages cite it.
struct ColmapLocations {
  std::map<uint32_t, std::string> images;    // image id -> "images.bin: byte 123"
  std::map<uint64_t, std::string> points3d;  // point id -> "points3D.txt: line 9"
};
void ValidateColmapModel(const ColmapModel& model, const ColmapLocations& where);

// Single files; `where` (optional) records each element's location for ValidateColmapModel.
void ParseColmapCamerasBinary(std::string_view data, const std::string& source, ColmapModel& model);
void ParseColmapImagesBinary(std::string_view data, const std::string& source, ColmapModel& model,
                             ColmapLocations* where = nullptr);
void ParseColmapPoints3DBinary(std::string_view data, const std::string& source, ColmapModel& model,
                               ColmapLocations* where = nullptr);
void ParseColmapCamerasText(std::string_view data, const std::string& source, ColmapModel& model);
void ParseColmapImagesText(std::string_view data, const std::string& source, ColmapModel& model,
                           ColmapLocations* where = nullptr);
void ParseColmapPoints3DText(std::string_view data, const std::string& source, ColmapModel& model,
                             ColmapLocations* where = nullptr);

}  // namespace cinepath::photogrammetry
