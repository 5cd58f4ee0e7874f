// Rule 2 of `cinepath optimize`: the output is never worse than its input (docs/optimize.md, "Never worse
// than the input"). Every hard limit is measured at every sample of a plan: the drone's and the lens's
// limits as `plan`'s own check takes them (MeasureLimits, with the terrain under the camera when
// there is a scene), the deviation from the input against each shot's max_deviation_m, and with a scene:
// the distance to the nearest surface against the clearance margin, the path between two samples passing
// through a surface, and the subject hidden by the scene (ray casts). A candidate is never worse when, for
// every limit and every sample, it breaks the limit by no more than the input breaks it anywhere in that
// sample's shot: a limit the input meets throughout a shot is met throughout it, one it breaks is broken
// nowhere in the shot by more than its worst there. A hidden subject and a step through a surface are
// taken frame by frame: a frame whose subject was seen stays seen, a step that was clear stays clear.
//
// When the solver's output is worse, the plan returned is input + alpha (output - input) over every
// optimized channel, with the largest alpha found never worse (1, else a fixed number of bisection steps
// from [0, 1]; alpha = 0 is the input itself): deterministic, and never worse by construction. Each group
// of samples between two cuts has its own alpha (its own variables; no limit is measured across a cut):
// a group whose whole change is never worse keeps it, whatever another group breaks.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/feasibility.h"
#include "core/json.h"
#include "core/trajectory.h"
#include "scene/ray_caster.h"
#include "scene/surface_distance.h"

namespace cinepath::optimizer {

// What the guard measures a plan with. Every vector has one entry per sample of the input.
struct GuardSetup {
  std::vector<bool> cut_before;                           // as CheckFeasibility takes it
  std::vector<int> shot_of_sample;                        // -1: none (the sample is then taken alone)
  std::vector<Eigen::Vector3d> origin_enu_m;              // the plan as given to `optimize` (the reference may be a
                                                          // cheaper preset's result): deviation is measured from it
  std::vector<double> max_deviation_m;                    // how far each sample may leave it
  std::vector<std::optional<Eigen::Vector3d>> aim_enu_m;  // the subject's aim point, where a shot has one
  const scene::RayCaster* caster = nullptr;               // the scene (or null): terrain, crossings, sight
  const scene::SurfaceDistance* surface = nullptr;        // the scene (or null): clearance
  double clearance_margin_m = 3.0;
  std::string scene_source;  // for the terrain check's messages
};

// Every limit of one plan, sample by sample, in a fixed order.
using LimitMeasure = std::vector<LimitSeries>;

// `input` is the reference a candidate must not be worse than: the plan as given, or in a later stage of
// the quality ladder the cheaper preset's accepted result (itself never worse than the plan as given).
class LimitGuard {
 public:
  LimitGuard(const Trajectory& input, GuardSetup setup);
  LimitMeasure Measure(const Trajectory& plan) const;
  const LimitMeasure& input() const { return input_measure_; }
  // The limits `candidate` breaks by more than the input at some sample (empty: never worse).
  std::vector<std::string> WorseThanInput(const LimitMeasure& candidate) const;
  // Per sample: whether `candidate` breaks some limit there by more than the input.
  std::vector<bool> WorseSamples(const LimitMeasure& candidate) const;

 private:
  const Trajectory& input_;
  GuardSetup setup_;
  LimitMeasure input_measure_;
  std::vector<std::vector<double>> allowed_;  // per limit and sample: the excess a candidate may have there
};

struct GuardedPlan {
  Trajectory plan;
  double alpha = 1;                    // the fraction of the solver's change kept (the least of group_alpha)
  std::vector<double> group_alpha;     // per group of samples between cuts
  std::vector<std::string> raw_broke;  // the limits the solver's own output made worse (empty: none)
  LimitMeasure measure;                // of `plan`
};

// The plan at alpha = 1 if it is never worse than the input, else the largest alpha found so in `steps`
// bisection steps (at least alpha = 0, the input). `at(alpha)` builds the plan for a fraction.
GuardedPlan KeepNeverWorse(const LimitGuard& guard, const std::function<Trajectory(double)>& at, int steps = 12);
// The same per group: `group_of_sample` numbers the groups from 0, `at(alphas)` builds the plan with alphas[g]
// of group g's change. Every group's alpha is 1 if the whole change is never worse; else the groups with a
// sample worse start at 0 and each (in order) gets the largest alpha found never worse with the others as
// they are then.
GuardedPlan KeepNeverWorseByGroup(const LimitGuard& guard, const std::vector<int>& group_of_sample,
                                  const std::function<Trajectory(const std::vector<double>&)>& at, int steps = 12);

// The report of the limits a plan still breaks ({limit, unit, limit, worst, shot, start_time_s,
// end_time_s, by, hint} per broken range, in time order) and the first as a one-line message (empty when
// none): what --strict refuses.
Json StillBroken(const LimitMeasure& measure, const Trajectory& plan, std::string* first_message);

}  // namespace cinepath::optimizer
