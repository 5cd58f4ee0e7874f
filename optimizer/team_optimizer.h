// `cinepath optimize` for several drones (core/team_plan.h): every drone's flight optimized as `optimize`
// does one (optimizer/optimizer.h), with two more terms against the other drones: `separation` (every
// pair at least the profiles' min_separation_m apart) and `out_of_shot` (no drone's body inside another's
// frame while that camera is live in the edit, or at any time without an edit). docs/optimize.md,
// "Several drones".
//
// Each drone is solved with the others held fixed (block coordinate descent), in two sweeps that split a
// breach between the drones it involves, so that the change is shared rather than taken by whichever
// drone comes first:
//   1. every drone against the others' planned paths, asking for half of each separation it misses
//      ((d + s) / 2 from the other's planned position: both move, and the pair ends about s apart);
//   2. every drone in order, again from its planned path, against the others' latest paths, asking for
//      the full separation: what the first sweep left is closed.
// A one-drone plan is optimized exactly as before (the same bytes). Deterministic: drones in plan order,
// each solve the same bytes on any number of threads (optimizer/banded_solver.h).
#pragma once

#include <string>

#include "core/json.h"
#include "core/team_plan.h"
#include "optimizer/optimize_options.h"
#include "scene/scene_mesh.h"

namespace cinepath::optimizer {

struct TeamOptimizeInput {
  TeamPlan plan;
  std::string plan_source = "plan.json";
  const scene::SceneMesh* mesh = nullptr;
  std::string scene_source;
};

struct TeamOptimizeResult {
  TeamPlan plan;        // optimized; team report and each flight's feasibility recomputed
  Json report;          // one-drone plans: OptimizePlan's report; teams: {"team": {...}, "drones": [{name, ...}]}
  std::string failure;  // empty when every limit holds, no team conflict remains and every subject is seen
};

TeamOptimizeResult OptimizeTeam(const TeamOptimizeInput& input, const OptimizeOptions& options);

}  // namespace cinepath::optimizer
