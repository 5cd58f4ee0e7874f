// QGroundControl / Mission Planner plain-text waypoint file, "QGC WPL 110" (docs/mission-formats.md §1):
// row 0 = home (current 1, frame 0, AMSL), then items from seq 1; exactly 12 TAB-separated fields;
// params and lat/lon with 8 decimals, altitude with 6 (as Mission Planner writes them).
#pragma once

#include <string>

#include "export/mavlink_mission.h"
#include "export/mission.h"

namespace cinepath::exporter {

std::string WriteQgcWpl(const Mission& mission, const MavMission& items);

}  // namespace cinepath::exporter
