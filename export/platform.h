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

// A drone (and its flight controller / app) as far as a mission cares.
struct DroneProfile {
  std::string name;
  double max_speed_mps = 15;
  double min_relative_alt_m = -200;
  double max_relative_alt_m = 500;
  double min_gimbal_pitch_deg = -90;
  double max_gimbal_pitch_deg = 30;
  int max_mission_items = 2000;  // MAVLink items (flight controller storage)
  int dji_drone_enum = 67;       // WPML droneInfo (M30 by default)
  int dji_drone_sub_enum = 0;
  int dji_payload_enum = 52;  // WPML payloadInfo
};
const DroneProfile& FindDroneProfile(const std::string& name);  // InputError listing known names
std::vector<std::string> DroneProfileNames();
// Default profile for a firmware: "px4-multirotor" or "ardupilot-copter".
const char* DefaultProfileName(Firmware firmware);

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
