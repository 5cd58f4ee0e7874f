// Safety checks before a mission is written: waypoint count, spacing, speed, altitude and gimbal
// range, finite values — against both the drone profile and the format's own limits.
#pragma once

#include <string>
#include <vector>

#include "core/drone_profile.h"
#include "export/mission.h"
#include "export/platform.h"

namespace cinepath::exporter {

struct Violation {
  int waypoint = -1;    // 0-based waypoint index; −1 for the mission as a whole
  std::string limit;    // e.g. "dji-msdk-json max speed 15 m/s"
  std::string message;  // the complete sentence shown to people
};

// `mavlink_item_count` is the number of MAVLink items the mission turns into (0 for DJI/Litchi).
std::vector<Violation> ValidateMission(const Mission& mission, Format format, const DroneProfile& profile,
                                       int mavlink_item_count);

}  // namespace cinepath::exporter
