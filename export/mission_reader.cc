#include "export/mission_reader.h"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include <fmt/format.h>

#include "core/error.h"
#include "core/file_io.h"

namespace cinepath::exporter {

namespace {

const char* CommandName(int command) {
  switch (command) {
    case mav::kNavWaypoint: return "NAV_WAYPOINT";
    case mav::kNavReturnToLaunch: return "NAV_RETURN_TO_LAUNCH";
    case mav::kNavTakeoff: return "NAV_TAKEOFF";
    case mav::kConditionYaw: return "CONDITION_YAW";
    case mav::kDoChangeSpeed: return "DO_CHANGE_SPEED";
    case mav::kDoSetRoiLocation: return "DO_SET_ROI_LOCATION";
    case mav::kDoSetRoiNone: return "DO_SET_ROI_NONE";
    case mav::kDoDigicamConfigure: return "DO_DIGICAM_CONFIGURE";
    case mav::kSetCameraZoom: return "SET_CAMERA_ZOOM";
    case mav::kSetCameraFocus: return "SET_CAMERA_FOCUS";
    case mav::kDoGimbalManagerPitchYaw: return "DO_GIMBAL_MANAGER_PITCHYAW";
    case mav::kVideoStartCapture: return "VIDEO_START_CAPTURE";
    case mav::kVideoStopCapture: return "VIDEO_STOP_CAPTURE";
    default: return nullptr;
  }
}

std::string CommandLabel(int command) {
  const char* name = CommandName(command);
  return name ? std::string(name) : "MAV_CMD " + std::to_string(command);
}

double ParseField(const std::string& token, const std::string& where) {
  double value = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) {
    throw InputError(Located(where, "'" + token + "' is not a number"));
  }
  return value;
}

int ParseInt(const std::string& token, const std::string& where) {
  int value = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) {
    throw InputError(Located(where, "'" + token + "' is not an integer"));
  }
  return value;
}

}  // namespace

ReadMission ParseQgcPlan(const std::string& text, const std::string& source) {
  const Json doc = ParseJsonText(text, source);
  const JsonField root(doc, source);
  if (!root.IsObject()) root.Fail("a .plan file is a JSON object");
  if (root["fileType"].AsString() != "Plan") root["fileType"].Fail("must be \"Plan\"");
  if (root["version"].AsInt() != 1) root["version"].Fail("must be 1");
  root["groundStation"].AsString();
  for (const char* key : {"mission", "geoFence", "rallyPoints"}) {
    if (!root[key].IsObject()) root[key].Fail("must be an object");
  }
  const JsonField mission = root["mission"];
  if (mission["version"].AsInt() != 2) mission["version"].Fail("must be 2");
  ReadMission out;
  out.kind = "qgc-plan";
  out.firmware_type = static_cast<int>(mission["firmwareType"].AsInt());
  const JsonField home = mission["plannedHomePosition"];
  if (!home.IsArray() || home.size() != 3) home.Fail("must be [lat, lon, alt]");
  out.home_lat_deg = home.At(0).AsDouble();
  out.home_lon_deg = home.At(1).AsDouble();
  out.home_amsl_m = home.At(2).AsDouble();
  for (const JsonField& item : mission["items"].Elements()) {
    if (item["type"].AsString() != "SimpleItem") item["type"].Fail("only SimpleItem is supported");
    MavItem m;
    m.command = static_cast<int>(item["command"].AsInt());
    m.frame = static_cast<int>(item["frame"].AsInt());
    m.autocontinue = item["autoContinue"].AsBool();
    const JsonField params = item["params"];
    if (!params.IsArray() || params.size() != 7) params.Fail("must hold exactly 7 params");
    for (size_t p = 0; p < 7; ++p) {
      const JsonField v = params.At(p);
      m.params[p] = v.IsNull() ? std::nan("") : v.AsDouble();
    }
    const Json& node = item.node();
    const int alt_keys =
        node.contains("AltitudeMode") + node.contains("Altitude") + node.contains("AMSLAltAboveTerrain");
    if (alt_keys != 0 && alt_keys != 3) {
      item.Fail("AltitudeMode, Altitude and AMSLAltAboveTerrain must appear together");
    }
    out.items.push_back(m);
  }
  return out;
}

ReadMission ParseQgcWpl(const std::string& text, const std::string& source) {
  std::istringstream stream(text);
  std::string line;
  int line_no = 0;
  ReadMission out;
  out.kind = "qgc-wpl";
  bool have_home = false;
  while (std::getline(stream, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = source + ": line " + std::to_string(line_no);
    if (line_no == 1) {
      if (line != "QGC WPL 110") throw InputError(Located(where, "header must be 'QGC WPL 110'"));
      continue;
    }
    std::vector<std::string> fields;
    size_t start = 0;
    while (true) {
      const size_t tab = line.find('\t', start);
      fields.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
      if (tab == std::string::npos) break;
      start = tab + 1;
    }
    if (fields.size() != 12) {
      throw InputError(Located(where, fmt::format("{} TAB-separated fields, expected 12", fields.size())));
    }
    const int seq = ParseInt(fields[0], where + ", field 1");
    if (seq != line_no - 2) throw InputError(Located(where, fmt::format("index {} out of sequence", seq)));
    MavItem item;
    item.frame = ParseInt(fields[2], where + ", field 3");
    item.command = ParseInt(fields[3], where + ", field 4");
    for (int p = 0; p < 7; ++p) item.params[p] = ParseField(fields[4 + p], where + ", field " + std::to_string(5 + p));
    item.autocontinue = ParseInt(fields[11], where + ", field 12") == 1;
    if (seq == 0) {
      out.home_lat_deg = item.params[4];
      out.home_lon_deg = item.params[5];
      out.home_amsl_m = item.params[6];
      have_home = true;
    } else {
      out.items.push_back(item);
    }
  }
  if (line_no == 0) throw InputError(Located(source, "empty file"));
  if (!have_home) throw InputError(Located(source, "no home row (seq 0)"));
  return out;
}

bool LooksLikeMission(const std::string& text) {
  if (text.rfind("QGC WPL", 0) == 0) return true;
  return text.find("\"fileType\"") != std::string::npos && text.find("\"Plan\"") != std::string::npos;
}

ReadMission ReadMissionFile(const std::filesystem::path& path) {
  const std::string text = ReadFileToString(path);
  const std::string source = path.string();
  if (text.rfind("QGC WPL", 0) == 0) return ParseQgcWpl(text, source);
  return ParseQgcPlan(text, source);
}

Json MissionSummaryJson(const ReadMission& mission) {
  Json j;
  j["kind"] = mission.kind;
  if (mission.firmware_type) {
    j["firmware"] = *mission.firmware_type == mav::kAutopilotPx4         ? "px4"
                    : *mission.firmware_type == mav::kAutopilotArduPilot ? "ardupilot"
                                                                         : "other";
  }
  j["home"] =
      Json{{"lat_deg", mission.home_lat_deg}, {"lon_deg", mission.home_lon_deg}, {"amsl_m", mission.home_amsl_m}};
  j["mission_items"] = static_cast<int>(mission.items.size());
  std::map<std::string, int> counts;
  Json waypoints = Json::array();
  for (const MavItem& item : mission.items) {
    ++counts[CommandLabel(item.command)];
    if (item.command == mav::kNavWaypoint) {
      waypoints.push_back(Json{
          {"lat_deg", item.params[4]}, {"lon_deg", item.params[5]}, {"alt_m", item.params[6]}, {"frame", item.frame}});
    }
  }
  Json commands = Json::object();
  for (const auto& [name, n] : counts) commands[name] = n;
  j["commands"] = commands;
  j["waypoints"] = waypoints;
  return j;
}

std::string MissionSummaryText(const ReadMission& mission) {
  int waypoints = 0;
  std::map<std::string, int> counts;
  for (const MavItem& item : mission.items) {
    ++counts[CommandLabel(item.command)];
    waypoints += item.command == mav::kNavWaypoint;
  }
  std::string out = fmt::format("{} mission: {} items, {} waypoints\n", mission.kind, mission.items.size(), waypoints);
  out += fmt::format("home: {:.8f}, {:.8f}, {:.2f} m AMSL\n", mission.home_lat_deg, mission.home_lon_deg,
                     mission.home_amsl_m);
  for (const auto& [name, n] : counts) out += fmt::format("  {:<28} {}\n", name, n);
  return out;
}

}  // namespace cinepath::exporter
