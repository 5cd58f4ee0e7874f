// The output formats and target firmwares, and what a format's limits are made of (docs/export.md).
// Each format is declared once, with its limits, in export/formats.h.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace cinepath::exporter {

enum class Format { kQgcPlan, kQgcWpl, kMavlinkBin, kDjiWpml, kDjiMsdkJson, kLitchiCsv, kGltfCamera, kNukeChan };
enum class Firmware { kPx4, kArduPilot };

const char* FirmwareName(Firmware firmware);  // "px4" | "ardupilot"
Firmware ParseFirmware(const std::string& name);

// What a file format itself allows (independent of the drone).
struct FormatLimits {
  int min_waypoints = 1;
  int max_waypoints = std::numeric_limits<int>::max();
  double min_speed_mps = 0;
  double max_speed_mps = std::numeric_limits<double>::infinity();
  double min_spacing_m = 0;  // 3-D distance between adjacent waypoints
  double max_spacing_m = std::numeric_limits<double>::infinity();
  double min_relative_alt_m = -std::numeric_limits<double>::infinity();
  double max_relative_alt_m = std::numeric_limits<double>::infinity();
  double min_gimbal_pitch_deg = -std::numeric_limits<double>::infinity();
  double max_gimbal_pitch_deg = std::numeric_limits<double>::infinity();
};

}  // namespace cinepath::exporter
