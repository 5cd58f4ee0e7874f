// What `cinepath optimize` is asked to do: the preset, the weights of the cost terms and the margins.
// docs/optimize.md gives every value and why; bench/RESULTS.md gives each preset's time and result.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/quality.h"

namespace ceres {
class Problem;
}

namespace cinepath::optimizer {

// Fuzzing only (tests/fuzz/fuzz_plan_optimize.cc): a solver run on each stage in place of Ceres' own, on
// the same problem from the same start. It gets the problem, its variable parameter blocks and, for each,
// the channels held fixed; it leaves the solution in the blocks and returns its iteration count.
using ExternalSolver = std::function<int(ceres::Problem* problem, const std::vector<double*>& blocks,
                                         const std::vector<std::vector<int>>& fixed_channels)>;

// Bench only (bench/optimize_vs_ipopt.cc): the same problem as a constrained one, over the same variables
// and from the same start. `goals`: every term but the hard limits (framing, depth of field, background
// blur, smoothness, the adherence pull and ridge, occlusion), its cost the objective 1/2 |r|^2. `limits`:
// one residual per hard limit (the drone's and the lens's limits, keep-out, clearance, the deviation
// allowed, a team's separation and frames), its signed margin g: the limit holds (at the value the
// product aims at) where g <= 0. Both problems have every knot block, with the fixed channels set the
// same way (a SubsetManifold, or constant); `blocks` and `fixed_channels` are as for ExternalSolver.
struct ConstrainedProblem {
  ceres::Problem* goals = nullptr;
  ceres::Problem* limits = nullptr;
  std::vector<double*> blocks;
  std::vector<std::vector<int>> fixed_channels;
};
// It leaves the solution in the blocks and returns its iteration count.
using ConstrainedSolver = std::function<int(const ConstrainedProblem& problem)>;

// The weight of each cost term: residuals are made dimensionless first (docs/optimize.md, "Costs"),
// so a weight says how much one unit of that term matters against one unit of another.
struct CostWeights {
  double smoothness = 1.0;   // jerk of the path change (per m/s^3), rates of the angle and lens changes
  double framing = 80.0;     // per frame width of screen offset, per e-fold of image height
  double sharpness = 200.0;  // per dioptre-relative excess outside the depth of field (stiff)
  double background = 50.0;  // per fraction of the blur goal missing
  double adherence = 0.5;    // per metre from the planned path (a gentle pull back)
  double deviation = 200.0;  // per metre beyond max_deviation_m (stiff)
  double ridge = 1e-3;       // per unit of every other change (keeps free channels where they were)
  double limits = 100.0;     // per fraction of a limit exceeded (stiff)
  double clearance = 100.0;  // per metre inside the clearance margin (stiff)
  double occlusion = 30.0;   // per metre from the nearest viewpoint with a clear line of sight
  double team = 100.0;       // several drones: per fraction of the separation missing, per metre into
                             // another drone's live frame (stiff)
};

struct OptimizeOptions {
  Quality quality = Quality::kStandard;
  double knot_spacing_s = 0.5;       // one set of variables per knot (docs/optimize.md, "Knots")
  int max_iterations = 100;          // per round
  double function_tolerance = 1e-8;  // Ceres: relative cost change that ends a round
  int visibility_rounds = 4;         // solve, re-check lines of sight, re-target the hidden frames, solve again
  int multiplier_rounds = 4;         // augmented Lagrangian: update the limits' multipliers, solve again
  // The stiff stage's goals on the coarse grid (every few samples, weighted), its limits at every sample
  // (docs/optimize.md, "Speed"): draft's trade of accuracy for time.
  bool goals_on_coarse_grid = false;
  double clearance_margin_m = 3.0;  // distance to the mesh the drone keeps
  double max_deviation_m = 5.0;     // default when a shot gives none
  double limit_margin = 0.02;       // limits are aimed at (1 - margin) of their value, so they hold after
  // The first solve's continuation (docs/optimize.md, "Limits as constraints"): the scale of the limits'
  // penalties in each stage, full weight (1) last. A decade a stage: from 1e-2 straight to 1 the soft
  // path was often too far outside the limits for the stiff stage to bring back in its iterations.
  std::vector<double> ramp = {1e-4, 1e-3, 1e-2, 1e-1, 1.0};
  CostWeights weights;
  ExternalSolver external_solver;  // empty: Ceres (always, outside the fuzz target)
  // Set: in place of every solve, its penalty ramp and its multiplier rounds (always empty, outside the
  // peer benchmark).
  ConstrainedSolver constrained_solver;
  // Bench only (bench/optimize_bench.cc, `--solver ceres`): Ceres' own Levenberg-Marquardt with its sparse
  // normal Cholesky in place of the banded solver (optimizer/banded_solver.h), on the same problem.
  bool ceres_solver = false;

  static OptimizeOptions ForQuality(Quality quality);
};

}  // namespace cinepath::optimizer
