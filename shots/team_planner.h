// `cinepath plan` for several drones (shots.json "drones"): each drone's shots planned as one flight
// (shots/planner.h), on one clock, then the edit's matched focus and the team checks
// (core/team_checks.h). docs/plan.md, "Several drones".
#pragma once

#include "core/team_plan.h"
#include "shots/planner.h"
#include "shots/shot_list.h"

namespace cinepath::shots {

// A list without drones (ShotList::drones) is one drone: a team of one flight named after its profile,
// `single` (written as a "cinepath.plan/1" plan). InputError (naming shots.json's JSON path) for an edit that
// cuts after the plan ends, or a matched focus whose outgoing shot has no subject.
TeamPlan PlanTeam(const ShotList& list, const PlanOptions& options = {});

}  // namespace cinepath::shots
