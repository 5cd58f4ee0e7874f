// `cinepath info plan.json` for a plan of several drones ("cinepath.plan/2"): per drone its profile,
// shots, duration, samples and feasibility, then the edit and the team report in short.
#pragma once

#include <string>

#include "core/json.h"
#include "core/team_plan.h"

namespace cinepath {

Json TeamPlanSummaryJson(const TeamPlan& plan);
std::string TeamPlanSummaryText(const TeamPlan& plan);

}  // namespace cinepath
