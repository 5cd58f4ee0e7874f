#include "export/qgc_plan.h"

#include <algorithm>
#include <cmath>

#include "core/json.h"

namespace cinepath::exporter {

std::string WriteQgcPlan(const Mission& mission, const MavMission& items, Firmware firmware, AltitudeRef ref) {
  const int alt_mode = ref == AltitudeRef::kRelative ? 1 : 2;  // QGC AltMode: 1 Relative, 2 Absolute
  Json json_items = Json::array();
  int do_jump_id = 1;  // QGC numbers items from 1 (home = 0)
  for (const MavItem& item : items.items) {
    Json j;
    j["type"] = "SimpleItem";
    j["command"] = item.command;
    j["frame"] = item.frame;
    j["autoContinue"] = item.autocontinue;
    j["doJumpId"] = do_jump_id++;
    Json params = Json::array();
    for (double p : item.params) params.push_back(p);
    j["params"] = params;
    if (item.IsGlobal()) {
      j["AltitudeMode"] = alt_mode;
      j["Altitude"] = item.params[6];
      j["AMSLAltAboveTerrain"] = nullptr;
    }
    json_items.push_back(j);
  }
  double max_speed = 0;
  for (const auto& wp : mission.waypoints) max_speed = std::max(max_speed, wp.speed_mps);

  Json plan;
  plan["fileType"] = "Plan";
  plan["version"] = 1;
  plan["groundStation"] = "cinepath";
  Json m;
  m["version"] = 2;
  m["firmwareType"] = firmware == Firmware::kPx4 ? mav::kAutopilotPx4 : mav::kAutopilotArduPilot;
  m["vehicleType"] = 2;   // MAV_TYPE_QUADROTOR
  m["cruiseSpeed"] = 15;  // integers: Mission Planner reads these as int
  m["hoverSpeed"] = std::max(1, static_cast<int>(std::lround(max_speed)));
  m["globalPlanAltitudeMode"] = alt_mode;
  m["plannedHomePosition"] = Json::array({mission.home.lat_deg, mission.home.lon_deg, mission.home.amsl_m});
  m["items"] = json_items;
  plan["mission"] = m;
  plan["geoFence"] = Json{{"version", 2}, {"circles", Json::array()}, {"polygons", Json::array()}};
  plan["rallyPoints"] = Json{{"version", 2}, {"points", Json::array()}};
  return DumpJson(plan);
}

}  // namespace cinepath::exporter
