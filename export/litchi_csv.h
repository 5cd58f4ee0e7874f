// Litchi mission CSV (docs/mission-formats.md §4.3): the 46-column header, one row per waypoint, metres, altitude
// mode 0 (relative to take-off = home), heading [0, 360), gimbal mode 2 (interpolate) with the
// waypoint's pitch, start recording (action 2) at the first waypoint and stop (action 3) at the last.
// Zoom, focus, aperture and gimbal yaw have no Litchi column: reported in `notes`.
#pragma once

#include <string>
#include <vector>

#include "export/mission.h"

namespace cinepath::exporter {

struct LitchiCsv {
  std::string text;
  std::vector<std::string> notes;
};
LitchiCsv WriteLitchiCsv(const Mission& mission);

}  // namespace cinepath::exporter
