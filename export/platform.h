// Output formats, target firmware and the limits of each drone platform and format
// (../shared/specs/missions.md: MAVLink 3.2–3.4, DJI 4.1–4.2, Litchi 4.3).
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace cinepath::exporter {

enum class Format { kQgcPlan, kQgcWpl, kMavlinkBin, kDjiWpml, kDjiMsdkJson, kLitchiCsv };
enum class Firmware { kPx4, kArduPilot };

const char* FormatName(Format format);        // "qgc-plan", ...
const char* FormatFileName(Format format);    // "mission.plan", ...
Format ParseFormat(const std::string& name);  // InputError listing the known names
bool IsMavlinkFormat(Format format);
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
FormatLimits LimitsOf(Format format);

}  // namespace cinepath::exporter
