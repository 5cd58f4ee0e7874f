// DJI MSDK v4 refuses adjacent waypoints closer than 0.5 m (docs/mission-formats.md §4.2). Slow or hovering parts
// of a plan (a pan on the spot, a locked-off shot) give such pairs; this merges every waypoint that is
// closer than the minimum to the last kept one into it: the kept waypoint takes over the merged one's
// recording stop and transit flag, and hovers (`hold_s`, written as STAY actions) until the merged
// one's time, so leg speeds and waypoint times still follow the plan. Heading and gimbal changes of
// the merged waypoints are lost; the merge is reported.
#pragma once

#include <string>
#include <vector>

#include "export/mission.h"

namespace cinepath::exporter {

// Returns the merged mission; appends a note to `notes` when anything was merged.
Mission MergeCloseWaypoints(const Mission& mission, double min_spacing_m, std::vector<std::string>& notes);

}  // namespace cinepath::exporter
