// Reference positions for georeferencing: one camera (image) position per line,
//   image_name lat_deg lon_deg alt_m
// the format COLMAP's model_aligner reads with --ref_is_gps 1 (spaces or tabs). Unlike model_aligner,
// lines whose first non-blank character is '#' are comments (model_aligner would take a '#' header as
// a reference, and with --alignment_type enu even as the origin), and blank lines are skipped. An
// image name may not contain spaces (as in COLMAP's text formats).
//
// The altitude's datum is not in the file: the caller says whether it is WGS84 ellipsoidal or AMSL
// (EGM96), see georeference.h AltitudeDatum.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace cinepath::photogrammetry {

struct ImageReference {
  std::string image_name;
  double lat_deg = 0;
  double lon_deg = 0;
  double alt_m = 0;   // in the datum the caller states
  std::string where;  // "refs.txt: line 3" — for messages
};

// InputError naming the file and line for a malformed line, a latitude outside [-90, 90], a longitude
// outside [-180, 360], non-finite values, or an image named twice.
std::vector<ImageReference> ParseReferences(std::string_view text, const std::string& source);
std::vector<ImageReference> ReadReferencesFile(const std::filesystem::path& path);

}  // namespace cinepath::photogrammetry
