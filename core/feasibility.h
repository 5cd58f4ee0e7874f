// The feasibility report: every sample of a planned flight checked against the drone's and the
// lens's limits, broken limits merged into time ranges.
//
// Rates come from finite differences on the per-frame samples (dt = 1 / frame rate), never across
// an explicit cut: speed and vertical rate by central differences, horizontal acceleration by the
// second difference, jerk (3-D) by the third difference, yaw / gimbal-pitch / lens rates by backward
// differences; focus distances are clamped to the hyperfocal distance first (moving focus between
// the hyperfocal distance and infinity changes nothing visible). The climb to the first sample and the stop after the
// last are not part of the plan.
#pragma once

#include <string>
#include <vector>

#include "core/ground.h"
#include "core/trajectory.h"

namespace cinepath {

// What the planner asked of the lens before clamping to the camera's ranges (one per sample).
struct LensRequest {
  double focal_length_mm = 0;
  double focus_distance_m = 0;  // +inf = infinity
  double f_number = 0;
};

// One limit measured at every sample: `values[k]` in `unit`, NaN where it is not measured (a rate across
// a cut, the terrain off the mesh). A minimum (`is_minimum`) is broken below `limit_value`, a maximum
// above it; Excess(k) is by how much (0 where it holds or is not measured, at most 1e300).
struct LimitSeries {
  std::string limit, unit;
  double limit_value = 0;
  bool is_minimum = false;
  std::vector<double> values;
  double Excess(size_t k) const;
};

// Whether a limit of the report (FeasibilityViolation::limit) is a minimum, broken below its value
// (altitude_min, subject_distance, terrain_clearance, ...), rather than a maximum.
bool IsMinimumLimit(const std::string& limit);

// The samples where `series` is broken merged into time ranges within a shot, each with its worst value.
std::vector<FeasibilityViolation> ViolationsOf(const LimitSeries& series, const Trajectory& plan);

// `cut_before[i]` is true when sample i starts a shot joined by an explicit cut (no derivative
// crosses it). `requests` may be empty (lens ranges are then checked on the samples themselves).
// `ground` (the scene's mesh, or null) adds terrain_clearance: the camera at least the drone's
// min_terrain_clearance_m above the highest surface under it; without it that check is listed in
// FeasibilityReport::skipped.
FeasibilityReport CheckFeasibility(const Trajectory& plan, const std::vector<bool>& cut_before,
                                   const std::vector<LensRequest>& requests, const Ground* ground = nullptr);
// The same limits, in the same order, sample by sample (what the optimizer compares, input against output).
std::vector<LimitSeries> MeasureLimits(const Trajectory& plan, const std::vector<bool>& cut_before,
                                       const std::vector<LensRequest>& requests, const Ground* ground = nullptr);

}  // namespace cinepath
