#include "export/platform.h"

#include "core/error.h"

namespace cinepath::exporter {

namespace {

struct FormatInfo {
  Format format;
  const char* name;
  const char* file_name;
};
constexpr FormatInfo kFormats[] = {
    {Format::kQgcPlan, "qgc-plan", "mission.plan"},
    {Format::kQgcWpl, "qgc-wpl", "mission.waypoints"},
    {Format::kMavlinkBin, "mavlink-bin", "mission.mavlink"},
    {Format::kDjiWpml, "dji-wpml", "mission.kmz"},
    {Format::kDjiMsdkJson, "dji-msdk-json", "mission.dji.json"},
    {Format::kLitchiCsv, "litchi-csv", "mission.litchi.csv"},
};

}  // namespace

const char* FormatName(Format format) {
  for (const auto& f : kFormats) {
    if (f.format == format) return f.name;
  }
  return "?";
}

const char* FormatFileName(Format format) {
  for (const auto& f : kFormats) {
    if (f.format == format) return f.file_name;
  }
  return "?";
}

Format ParseFormat(const std::string& name) {
  std::string known;
  for (const auto& f : kFormats) {
    if (name == f.name) return f.format;
    known += known.empty() ? f.name : std::string(", ") + f.name;
  }
  throw InputError("formats: unknown format '" + name + "' (known: " + known + ")");
}

bool IsMavlinkFormat(Format format) {
  return format == Format::kQgcPlan || format == Format::kQgcWpl || format == Format::kMavlinkBin;
}

const char* FirmwareName(Firmware firmware) { return firmware == Firmware::kPx4 ? "px4" : "ardupilot"; }

Firmware ParseFirmware(const std::string& name) {
  if (name == "px4") return Firmware::kPx4;
  if (name == "ardupilot") return Firmware::kArduPilot;
  throw InputError("firmware: unknown firmware '" + name + "' (known: px4, ardupilot)");
}

FormatLimits LimitsOf(Format format) {
  FormatLimits l;
  switch (format) {
    case Format::kQgcPlan:
    case Format::kQgcWpl:
    case Format::kMavlinkBin:
      l.max_waypoints = 65535;  // seq is uint16
      break;
    case Format::kDjiWpml:
      // MSDK v5 refuses fewer than 2 or more than 65535 waypoints; speeds [1, 15] m/s. A slower leg
      // is flown at 1 m/s followed by a hover that keeps the timing (dji_wpml.h), so no minimum here.
      l.min_waypoints = 2;
      l.max_waypoints = 65535;
      l.max_speed_mps = 15;
      break;
    case Format::kDjiMsdkJson:
      // MSDK v4 WaypointMission: 2–99 waypoints, 0.5–2000 m apart, altitude −200..500 m relative,
      // gimbal pitch −90..0, speed 0..15 m/s.
      l.min_waypoints = 2;
      l.max_waypoints = 99;
      l.max_speed_mps = 15;
      l.min_spacing_m = 0.5;
      l.max_spacing_m = 2000;
      l.min_relative_alt_m = -200;
      l.max_relative_alt_m = 500;
      l.min_gimbal_pitch_deg = -90;
      l.max_gimbal_pitch_deg = 0;
      break;
    case Format::kLitchiCsv:
      // Litchi: up to 10 000 waypoints (since 2022); DJI speeds up to 15 m/s; gimbal −90..30.
      l.min_waypoints = 2;
      l.max_waypoints = 10000;
      l.max_speed_mps = 15;
      l.min_gimbal_pitch_deg = -90;
      l.max_gimbal_pitch_deg = 30;
      break;
  }
  return l;
}

}  // namespace cinepath::exporter
