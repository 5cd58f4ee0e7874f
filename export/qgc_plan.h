// QGroundControl .plan (JSON, file version 1, mission version 2; docs/mission-formats.md §2): the three
// top-level objects, SimpleItems with exactly 7 params, boolean autoContinue, AltitudeMode / Altitude /
// AMSLAltAboveTerrain together on items that carry an altitude.
#pragma once

#include <string>

#include "export/mavlink_mission.h"
#include "export/mission.h"

namespace cinepath::exporter {

std::string WriteQgcPlan(const Mission& mission, const MavMission& items, Firmware firmware, AltitudeRef ref);

}  // namespace cinepath::exporter
