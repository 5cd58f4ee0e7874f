// `cinepath optimize`: a plan's drone path, camera orientation, focal length, focus and aperture solved
// together, as one least-squares problem over the whole plan (Ceres), against the scene's mesh when
// there is one. docs/optimize.md describes the problem, every cost and weight, and the report.
//
// The variables are a change to the plan (optimizer/sample_model.h), a C2 spline through knots
// (optimizer/knot_spline.h); a plan with nothing to improve has zero cost and comes back unchanged.
// Only what the plan asks for is modelled: no clearance or occlusion terms without a mesh, no depth of
// field terms for a shot without goals, and a lens channel no term touches stays exactly as planned.
// The output is a plan of the same schema, its feasibility recomputed with `plan`'s own check. It is never
// worse than the input in any hard limit at any sample (optimizer/limit_guard.h), and a dearer preset runs
// the cheaper ones first and keeps its own result only when its objective is no larger (docs/optimize.md,
// "The quality ladder"). Deterministic: terms added in sample order, summed in chunks the problem fixes
// (optimizer/banded_solver.h), so the same bytes on any number of threads.
#pragma once

#include <string>

#include "core/json.h"
#include "core/trajectory.h"
#include "optimizer/optimize_options.h"
#include "scene/scene_mesh.h"

namespace cinepath::optimizer {

// Another drone of a team (optimizer/team_optimizer.h), held fixed while this plan is optimized: this
// drone keeps `separation_m[k]` from it and stays out of its frame at the samples where `live[k]`.
// Every vector has one entry per sample of the plan being optimized.
struct OtherDrone {
  std::string name;
  double body_radius_m = 0.4;
  CameraSpec camera;
  std::vector<TrajectorySample> samples;  // its pose and lens on this plan's clock
  std::vector<double> separation_m;
  std::vector<bool> live;
};
// This drone's own camera is live at sample k (its frame must not hold the others): `own_live[k]`.

struct OptimizeInput {
  std::vector<OtherDrone> others;  // several drones only
  std::vector<bool> own_live;      // with others: one per sample
  Trajectory plan;
  std::string plan_source = "plan.json";   // for messages
  const scene::SceneMesh* mesh = nullptr;  // the scene (ENU, the plan's frame), or null
  std::string scene_source;                // scene.json's name, for the record
};

struct OptimizeResult {
  Trajectory plan;  // optimized, with `optimized` filled in and feasibility recomputed
  Json report;      // report.json (docs/optimize.md, "Report")
  // Empty when every hard limit holds and every frame sees its subject; else the first limit still broken,
  // with its shot, time range, worst value and a hint (report.json's guard.still_broken; what --strict
  // refuses).
  std::string failure;
};

OptimizeResult OptimizePlan(const OptimizeInput& input, const OptimizeOptions& options);

// Bench only (bench/optimize_vs_ipopt.cc): the cost of each term on `plan`, a result of optimizing
// `input.plan`, taken as the quality ladder takes its objective: every change zero, the goals aimed where
// the input put them. One function of the plan, whichever solver or preset produced it.
Json PlanTermCosts(const OptimizeInput& input, const Trajectory& plan, const OptimizeOptions& options);

}  // namespace cinepath::optimizer
