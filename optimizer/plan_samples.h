// The plan cut into what the optimizer works on: groups of samples between explicit cuts (the change is
// one spline per group, so nothing is smoothed across a cut), the knots of each group, and every
// sample's fixed base (optimizer/sample_model.h) with the planned path's finite-difference rates.
#pragma once

#include <vector>

#include "core/trajectory.h"
#include "optimizer/knot_spline.h"
#include "optimizer/sample_model.h"

namespace cinepath::optimizer {

struct SampleGroup {
  size_t first_sample = 0, end_sample = 0;  // [first, end)
  int first_knot = 0;                       // index of its first knot in the problem's knot list
  KnotSpline spline{0, 0, 1};
  // True when the planned path breaks the acceleration or jerk limit here. A change that is itself C2
  // cannot cancel a jump in acceleration, so such a group's path is first replaced by its least-squares
  // C2 spline fit (same knots), and the change is added to that (docs/optimize.md, "Knots").
  bool refit = false;
};

struct PlanSamples {
  std::vector<SampleGroup> groups;
  std::vector<int> group_of_sample;
  std::vector<int> shot_of_sample;  // index into Trajectory::shots, -1 when the sample names none
  std::vector<bool> cut_before;     // as CheckFeasibility takes it
  std::vector<SampleBase> bases;
  int num_knots = 0;
};

// InputError (naming `source`) for a plan the optimizer cannot read: no samples, a sample naming an
// unknown shot, non-finite values. Without `allow_refit` no group is refit: every base is the plan's own
// sample (a stage that starts from a cheaper preset's result, whose change must be zero there).
PlanSamples SplitPlan(const Trajectory& plan, double knot_spacing_s, const std::string& source,
                      bool allow_refit = true);

// Least-squares control points of the group's spline through the planned positions (with a tiny
// third-difference penalty, so that knots no sample pins stay put): what a refit group starts from.
std::vector<Eigen::Vector3d> FitGroupPath(const Trajectory& plan, const SampleGroup& group);

}  // namespace cinepath::optimizer
