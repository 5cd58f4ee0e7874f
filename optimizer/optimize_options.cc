#include "optimizer/optimize_options.h"

#include "core/error.h"

namespace cinepath::optimizer {

OptimizeOptions OptimizeOptions::ForQuality(Quality quality) {
  // {knot spacing s, iterations per solve, function tolerance, visibility rounds, multiplier rounds, goals on
  // the coarse grid}
  // (docs/optimize.md).
  struct Preset {
    double knot_spacing_s;
    int max_iterations;
    double function_tolerance;
    int visibility_rounds;
    int multiplier_rounds;
    bool goals_on_coarse_grid;
  };
  static constexpr Preset kDraft{1.0, 30, 1e-5, 1, 4, true}, kStandard{0.5, 100, 1e-8, 4, 6, false},
      kFinal{0.25, 300, 1e-10, 6, 8, false};
  const Preset& p = quality == Quality::kDraft ? kDraft : quality == Quality::kFinal ? kFinal : kStandard;
  OptimizeOptions o;
  o.quality = quality;
  o.knot_spacing_s = p.knot_spacing_s;
  o.max_iterations = p.max_iterations;
  o.function_tolerance = p.function_tolerance;
  o.visibility_rounds = p.visibility_rounds;
  o.multiplier_rounds = p.multiplier_rounds;
  o.goals_on_coarse_grid = p.goals_on_coarse_grid;
  return o;
}

}  // namespace cinepath::optimizer
