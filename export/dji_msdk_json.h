// DJI Mobile SDK v4 WaypointMission as JSON (docs/mission-formats.md §4.2; no official file format exists, so the
// SDK's own field names are serialized). Altitudes relative to take-off (= home); heading in
// [−180, 180] with USING_WAYPOINT_HEADING; gimbalPitch per waypoint (gimbalPitchRotationEnabled);
// START_RECORD at the first waypoint, STOP_RECORD at the last. Zoom, focus, aperture and gimbal yaw
// have no MSDK v4 waypoint field: reported in `notes`.
#pragma once

#include <string>
#include <vector>

#include "export/mission.h"

namespace cinepath::exporter {

struct MsdkJson {
  std::string text;
  std::vector<std::string> notes;
};
MsdkJson WriteDjiMsdkJson(const Mission& mission);

}  // namespace cinepath::exporter
