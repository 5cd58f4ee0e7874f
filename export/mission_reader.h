// Reading MAVLink missions back — our own .plan (QGC JSON) and .waypoints ("QGC WPL 110") — for
// `cinepath info` and round-trip checks. Follows QGC's loading rules: .plan needs fileType "Plan",
// version 1, the mission/geoFence/rallyPoints objects, 7 params per SimpleItem, boolean autoContinue;
// WPL needs the "QGC WPL 110" header and exactly 12 TAB-separated fields per line, row 0 = home.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/json.h"
#include "export/mavlink_mission.h"

namespace cinepath::exporter {

struct ReadMission {
  std::string kind;                  // "qgc-plan" | "qgc-wpl"
  std::optional<int> firmware_type;  // MAV_AUTOPILOT (.plan only)
  double home_lat_deg = 0;
  double home_lon_deg = 0;
  double home_amsl_m = 0;
  std::vector<MavItem> items;  // without home
};

// InputError naming the file and the field / line on anything malformed.
ReadMission ParseQgcPlan(const std::string& text, const std::string& source);
ReadMission ParseQgcWpl(const std::string& text, const std::string& source);
// Picks the parser by content ("QGC WPL" header or JSON object).
ReadMission ReadMissionFile(const std::filesystem::path& path);
// True when the file looks like a mission this reader understands.
bool LooksLikeMission(const std::string& text);

// Summary for `cinepath info`: counts per command, positions of NAV_WAYPOINT items.
Json MissionSummaryJson(const ReadMission& mission);
std::string MissionSummaryText(const ReadMission& mission);

}  // namespace cinepath::exporter
