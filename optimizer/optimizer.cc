#include "optimizer/optimizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <type_traits>

#include <ceres/ceres.h>

#include "core/ceres_logging.h"
#include "core/error.h"
#include "core/feasibility.h"
#include "core/geodesy.h"
#include "core/ground.h"
#include "core/local_level.h"
#include "core/number_format.h"
#include "core/optics.h"
#include "core/rotation.h"
#include "optimizer/banded_solver.h"
#include "optimizer/clearance_cost.h"
#include "optimizer/cost_terms.h"
#include "optimizer/limit_guard.h"
#include "optimizer/linear_cost_function.h"
#include "optimizer/plan_samples.h"
#include "optimizer/retime.h"
#include "optimizer/sample_cost_function.h"
#include "optimizer/state_cost_function.h"
#include "optimizer/visibility_targets.h"
#include "scene/caster_ground.h"
#include "scene/ray_caster.h"
#include "scene/surface_distance.h"

namespace cinepath::optimizer {
namespace {

using Knot = std::array<double, kNumChannels>;
constexpr double kRadToDeg = 180.0 / M_PI;

// The channels a `hold` name covers.
std::vector<int> ChannelsOf(const std::string& name) {
  if (name == "position") return {kEast, kNorth, kUp};
  if (name == "orientation") return {kYaw, kTilt};
  if (name == "focal_length") return {kLogFocal};
  if (name == "focus") return {kDioptre};
  if (name == "aperture") return {kStops};
  return {};
}

// What one shot asks of the optimizer.
struct ShotSettings {
  const ShotSpan* span = nullptr;
  std::set<int> held;  // channels
  double max_deviation_m = 5;
  const SubjectTrack* subject = nullptr;
  std::vector<const SubjectTrack*> sharp;  // DoF goals (empty: none)
  bool background = false;
  // The focus follows an actor (the intent's "follow" or "rack"): the actor at each time, racks in order.
  bool focus_follows = false;
  std::vector<std::pair<RackIntent, const SubjectTrack*>> racks;
};

// The actor the focus follows at `time_s` in a shot whose focus follows one; none in the middle of a rack.
const SubjectTrack* FollowedActor(const ShotSettings& s, double time_s) {
  const double tau = time_s - s.span->start_time_s;
  const SubjectTrack* current = s.subject;
  for (const auto& [rack, track] : s.racks) {
    if (tau <= rack.at_s) break;
    if (tau < rack.at_s + rack.duration_s) return nullptr;
    current = track;
  }
  return current;
}

// The corridor of the scene the flight can reach, and the query structures built on it: built once from
// the input plan, shared by every stage of the quality ladder.
struct SceneIndex {
  size_t faces_in_scene = 0;
  scene::SceneMesh corridor;
  std::unique_ptr<scene::SurfaceDistance> surface;  // null without a scene
  std::unique_ptr<scene::RayCaster> caster;         // null when the corridor has no faces
  std::unique_ptr<scene::RayCaster> full_caster;    // background distances, only when a shot asks
  double takeoff_up_m = 0;                          // the ground under the input's first sample
  double build_s = 0;
};

Eigen::Vector3d AimPoint(const SubjectTrack& track, size_t k) {
  return track.positions_enu_m[k] + Eigen::Vector3d(0, 0, track.height_m / 2.0);
}

const SubjectTrack* FindTrack(const Trajectory& plan, const std::string& name, const std::string& where) {
  for (const auto& t : plan.subjects) {
    if (t.name == name) return &t;
  }
  throw InputError(where + ": no subject named \"" + name + "\" in the plan's subjects");
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

// The corridor: the bounds of the input's samples and the subjects' aim points grown by the largest
// deviation allowed plus the margin plus 1 m, down to the bottom of the mesh (the ground under the
// take-off point).
std::shared_ptr<const SceneIndex> IndexScene(const OptimizeInput& input, const OptimizeOptions& options) {
  auto index = std::make_shared<SceneIndex>();
  if (!input.mesh) return index;
  const Trajectory& plan = input.plan;
  const auto start = std::chrono::steady_clock::now();
  index->faces_in_scene = input.mesh->num_faces();
  double reach = options.clearance_margin_m + 1.0;
  bool background_goal = false;
  for (const auto& span : plan.shots) {
    reach = std::max(reach,
                     span.intent.max_deviation_m.value_or(options.max_deviation_m) + options.clearance_margin_m + 1.0);
    background_goal = background_goal || span.intent.background_blur_px.has_value();
  }
  Eigen::AlignedBox3d box;
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    box.extend(plan.samples[k].position_enu_m);
    for (const auto& t : plan.subjects) box.extend(AimPoint(t, k));
  }
  box.min() -= Eigen::Vector3d::Constant(reach);
  box.max() += Eigen::Vector3d::Constant(reach);
  const Eigen::AlignedBox3d bounds = input.mesh->Bounds();
  if (!bounds.isEmpty()) box.min().z() = std::min(box.min().z(), bounds.min().z() - 1.0);  // the ground under it
  index->corridor = scene::CropToBox(*input.mesh, box);
  index->surface = std::make_unique<scene::SurfaceDistance>(index->corridor);
  if (index->corridor.num_faces() > 0) {
    index->caster = std::make_unique<scene::RayCaster>(index->corridor);
    const auto& first = plan.samples.front().position_enu_m;
    if (const auto hit = index->caster->SurfaceBelow(first.x(), first.y()))
      index->takeoff_up_m = hit->position_enu_m.z();
  }
  index->build_s = Seconds(start);
  if (background_goal && input.mesh->num_faces() > 0)
    // (one ray per sample: a cheaper build pays)
    index->full_caster = std::make_unique<scene::RayCaster>(*input.mesh, scene::RayCaster::BuildQuality::kLow);
  return index;
}

// The constrained peer (OptimizeOptions::constrained_solver): the deviation allowed at a knot as a signed
// margin, (|change| - allowed) / max(allowed, 1 m), the argument of the adherence's hinge.
struct DeviationMargin {
  double max_deviation_m = 5;
  template <typename T>
  bool operator()(const T* k, T* r) const {
    r[0] = (SafeNorm(Vec3T<T>(k[kEast], k[kNorth], k[kUp])) - T(max_deviation_m)) / std::max(max_deviation_m, 1.0);
    return true;
  }
};

// The constrained peer: rows `rows` of a term's signed margins (owned). A margin no longer finite (an
// out-of-shot margin with the body behind the camera: no such limit there) reads -1, holding, with a zero
// derivative.
class MarginRows : public ceres::CostFunction {
 public:
  MarginRows(ceres::CostFunction* margins, std::vector<int> rows) : margins_(margins), rows_(std::move(rows)) {
    set_num_residuals(static_cast<int>(rows_.size()));
    *mutable_parameter_block_sizes() = margins->parameter_block_sizes();
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const auto& sizes = parameter_block_sizes();
    const int n = margins_->num_residuals();
    std::vector<double> all(n);
    std::vector<std::vector<double>> full(sizes.size());
    std::vector<double*> full_blocks(sizes.size(), nullptr);
    for (size_t j = 0; jacobians && j < sizes.size(); ++j) {
      if (!jacobians[j]) continue;
      full[j].resize(n * sizes[j]);
      full_blocks[j] = full[j].data();
    }
    if (!margins_->Evaluate(parameters, all.data(), jacobians ? full_blocks.data() : nullptr)) return false;
    for (size_t i = 0; i < rows_.size(); ++i) {
      const bool finite = std::isfinite(all[rows_[i]]);
      residuals[i] = finite ? all[rows_[i]] : -1.0;
      for (size_t j = 0; jacobians && j < sizes.size(); ++j) {
        if (!jacobians[j]) continue;
        for (int c = 0; c < sizes[j]; ++c)
          jacobians[j][i * sizes[j] + c] = finite ? full[j][rows_[i] * sizes[j] + c] : 0.0;
      }
    }
    return true;
  }

 private:
  std::unique_ptr<ceres::CostFunction> margins_;
  std::vector<int> rows_;
};

// One stage of the ladder: the change to `base` (the input itself, or the cheaper preset's accepted result)
// solved with `options`, its goals aimed where the input put them (`targets`: the first stage's samples,
// null in the first stage itself). A stage that starts from a result is not refit: its change is zero
// there, and the guard keeps it never worse than that result.
class PlanOptimizer {
 public:
  PlanOptimizer(const OptimizeInput& input, const Trajectory& base, const OptimizeOptions& options,
                std::shared_ptr<const SceneIndex> scene, const PlanSamples* targets)
      : input_(input), plan_(base), options_(options), scene_(std::move(scene)), targets_(targets) {}
  OptimizeResult Run();
  // The ladder's objective of the base: its goal and limit terms (not the smoothness and adherence of a
  // change, nor the occlusion targets), every change zero.
  double Objective();
  // The cost of every term of the base, every change zero (PlanTermCosts).
  Json BaseTermCosts() {
    Prepare();
    double total = 0;
    return TermCosts(&total);
  }
  const PlanSamples& samples() const { return split_; }

 private:
  void Prepare();
  double GoalCost();
  void ReadShots();
  void MarkFreeChannels();
  void AddTerms();
  // Adds the limits of every sample left out of the problem that a solve brought within kLimitRecheck of a
  // limit; returns how many.
  size_t AddLimitsNearTheirBounds();
  void AddLimitsTerm(const SampleBase& base, int shot);
  std::array<const double*, 4> KnotsOf(const SampleBase& base) const;  // the sample's four knots
  std::array<const double*, 4> KnotsFrom(int first_knot) const;
  // The channels the change may move at a sample (kEast: any of the position's).
  std::array<bool, kNumChannels> FreeChannels(const SampleBase& base) const;
  // The limits cost of the samples left out: a constant (their free limits hold with room; the others do
  // not move), counted where costs are reported so that leaving them out changes no figure.
  double ScreenedLimitsCost() const;
  // A sample's limits join the problem from the start when a limit is within this fraction of its aimed
  // value, and after a solve when one is within kLimitRecheck (docs/optimize.md, "Limits left out").
  static constexpr double kLimitScreen = 0.25, kLimitRecheck = 0.1;
  static constexpr int kLimitRows = 4;
  size_t AddVisibilityTargets();
  // How far past the first clear viewpoint a target is set: the pull stops just short of its target.
  static constexpr double kTargetOvershootM = 0.75;
  void Solve(bool ramp);
  void SolveBandedStage(ceres::Problem* problem);
  // Solves again with the multipliers of the hard limits updated until they hold (docs/optimize.md,
  // "Limits as constraints"), at most options_.multiplier_rounds times.
  void SolveUntilTheLimitsHold();
  // The augmented Lagrangian's update of every constraint in the problem; returns the largest violation
  // (per unit of its limit) before it. ResetMultipliers: every shift back to zero (the plain penalties).
  double UpdateMultipliers();
  void ResetMultipliers();
  // A hard limit in the problem: its multiplier update (argument true: reset) and the names of its limits
  // whose multiplier is positive (the limits that held the goals back), in its shot (-1: none).
  struct Constraint {
    int shot = -1;
    std::function<double(bool)> update;
    std::function<void(std::set<std::string>*)> binding;
    std::function<void(ceres::Problem*)> margin;  // the constrained peer: adds its signed margins (SolveConstrained)
  };
  // A one-sample constraint functor in the problem (the problem owns it), named `name` (LimitsCost: each
  // residual by its own name).
  template <typename Functor>
  void AddConstraint(Functor* f, const SampleBase& base, int shot, const char* name) {
    const int first = base.knots.first_knot;
    Constraint c;
    c.shot = shot;
    c.update = [this, f, first](bool reset) {
      if (reset) {
        f->shift = decltype(f->shift){};
        return 0.0;
      }
      return f->UpdateShifts(KnotsFrom(first).data());
    };
    c.margin = [this, f, first](ceres::Problem* limits) { AddMargin(*f, first, limits); };
    c.binding = [f, name](std::set<std::string>* names) {
      if constexpr (std::is_same_v<Functor, LimitsCost>) {
        for (int i = 0; i < LimitsCost::kNumResiduals; ++i) {
          if (f->shift[i] > 0) names->insert(LimitsCost::kLimitName[i]);
        }
      } else if (f->shift > 0) {
        names->insert(name);
      }
    };
    constraints_.push_back(std::move(c));
  }
  std::vector<Constraint> constraints_;  // in the order they joined the problem
  // The constrained peer (OptimizeOptions::constrained_solver): the goal terms as its objective, every hard
  // limit's signed margin as its constraint, solved by it in place of Solve's Ceres stages.
  void SolveConstrained();
  // The peer's constraints of a one-sample constraint functor: its hinges' arguments (LimitsCost: those of
  // its free channels) as residuals of `limits`.
  template <typename Functor>
  void AddMargin(const Functor& f, int first_knot, ceres::Problem* limits) const {
    constexpr bool kLimits = std::is_same_v<Functor, LimitsCost>;
    auto* margins = new Functor(f);
    margins->raw = true;
    std::vector<int> rows = {0};
    if constexpr (kLimits) {
      rows.clear();
      for (int i = 0; i < LimitsCost::kNumResiduals; ++i) {
        if (f.free[LimitsCost::kChannelOf[i]]) rows.push_back(i);
      }
    }
    using Cost = StateCostFunction<Functor, kLimits ? kValuesAndRates : kValues>;
    AddMarginRows(new Cost(margins, kLimits ? LimitsCost::kNumResiduals : 1), rows, first_knot, limits);
  }
  // Adds `rows` of `margins` (owned) on the four knots from `first_knot`, less those not finite at the
  // current knots (a limit the sample does not have: the rates of a plan's first sample).
  void AddMarginRows(ceres::CostFunction* margins, std::vector<int> rows, int first_knot, ceres::Problem* limits) const;
  // The variable knot blocks and the channels fixed in each (FixChannels).
  void VariableBlocks(std::vector<double*>* blocks, std::vector<std::vector<int>>* fixed);
  std::vector<const AdherenceCost*> adherence_;  // per knot (the problem owns them)
  // Per shot, the limits whose multiplier was positive at the end of the solve (Report).
  std::vector<std::set<std::string>> binding_;
  // A solve within this much of every limit's aimed value (per unit of the limit) needs no other round.
  static constexpr double kConstraintTolerance = 1e-3;
  SampleState<double> StateAt(const SampleBase& base) const;
  // The plan with `alpha[g]` of the change in each group g of samples between cuts: input + alpha (output -
  // input) over every optimized channel (alpha = 1 is the solver's output, 0 the input itself).
  Trajectory Apply(const std::vector<double>& alpha) const;
  // The guard (optimizer/limit_guard.h) on Apply, each group with its own alpha.
  GuardedPlan Guarded(const LimitGuard& guard) const {
    return KeepNeverWorseByGroup(guard, split_.group_of_sample,
                                 [&](const std::vector<double>& alpha) { return Apply(alpha); });
  }
  // Every knot times the alpha of its group, in place (the problem holds the knots' addresses).
  void ScaleKnots(const std::vector<double>& alpha);
  // GoalCost with `alpha[g]` of the change in each group g.
  double ObjectiveAt(const std::vector<double>& alpha);
  // When the guard cut the change (alpha < 1: the soft stages led the path where the stiff stage and the
  // multiplier rounds could not bring every limit back), a second solve from the plan as given with the
  // limits at full weight from the first step; the guarded result with the smaller objective is kept, and
  // the report says what was tried (null: nothing was). Not for a stage that starts from a cheaper preset's
  // result: it runs at full weight already.
  Json RetryAtFullWeight(const LimitGuard& guard, GuardedPlan* kept);
  Json Report(const Trajectory& optimized, const Json& before_terms, const Json& after_terms, double total_before,
              double total_after) const;
  Json TermCosts(double* total);
  std::set<std::string> TermNames() const;  // of the terms in blocks of their own and of the parts
  GuardSetup GuardSetupFor() const;
  std::vector<Eigen::Vector3d> Positions(bool changed) const;
  double BlockedFraction(const Trajectory& plan, size_t* first_blocked) const;

  template <typename Functor>
  void AddSampleTerm(const std::string& term, Functor* functor, const SampleBase& base, int residuals) {
    // Differentiated through the sample's state (optimizer/state_cost_function.h): only the limits read
    // rates, and their 19 hinges, seldom more than two of them active at a sample, go in kLimitRows rows.
    constexpr bool kLimits = std::is_same_v<Functor, LimitsCost>;
    using Cost = StateCostFunction<Functor, kLimits ? kValuesAndRates : kValues>;
    AddOneSampleTerm(term, std::make_unique<Cost>(functor, residuals, kLimits ? kLimitRows : 0), base);
  }
  // A one-sample term: a part of its sample's block while AddTerms builds it (sample_block_), else (the limits
  // that join later, the occlusion targets) a block of its own.
  template <typename Cost>
  void AddOneSampleTerm(const std::string& term, std::unique_ptr<Cost> cost, const SampleBase& base) {
    if (!sample_block_) {
      AddBlock(term, cost.release(), base.knots.first_knot, SampleOf(base));
      return;
    }
    parts_[term].push_back({cost.get(), base.knots.first_knot});
    sample_block_->Add(std::move(cost), IsStiff(term), IsGoal(term));
  }
  // `sample`: the plan sample of a one-sample term (-1: a term of a segment or a knot), for the coarse grid.
  void AddBlock(const std::string& term, ceres::CostFunction* cost, int first_knot, int sample = -1) {
    terms_[term].push_back(AddResidual(cost, IsStiff(term) ? stiffness_.get() : nullptr, first_knot, sample));
  }
  ceres::ResidualBlockId AddResidual(ceres::CostFunction* cost, ceres::LossFunction* loss, int first_knot, int sample) {
    std::vector<double*> blocks;
    for (int j = 0; j < 4; ++j) blocks.push_back(knots_[first_knot + j].data());
    const ceres::ResidualBlockId id = problem_.AddResidualBlock(cost, loss, blocks);
    block_sample_[id] = sample;
    ++problem_generation_;
    return id;
  }
  // A one-sample term inside its sample's block (SampleCostFunction owns it), with its four knots.
  struct Part {
    const ceres::CostFunction* cost;
    int first_knot;
  };
  // The cost of terms in blocks of their own, and of parts, with the knots as they are now.
  double BlocksCost(const std::vector<ceres::ResidualBlockId>& ids);
  double PartsCost(const std::vector<Part>& parts) const;
  // The index of a sample's base in split_.bases (-1: a copy, not one of them).
  int SampleOf(const SampleBase& base) const {
    const auto* first = split_.bases.data();
    return &base >= first && &base < first + split_.bases.size() ? static_cast<int>(&base - first) : -1;
  }
  // The coarse grid (docs/optimize.md, "Speed"): the soft continuation stages solve a problem with every
  // segment and knot term and the one-sample terms of every kCoarseStride-th sample only, each weighted
  // by the stride, so that the sums still approximate the same integrals over time; built on first use.
  ceres::Problem* CoarseProblem();
  int CoarseStride() const;
  // The coarse grid of goals (OptimizeOptions::goals_on_coarse_grid, docs/optimize.md, "Speed"): the stiff
  // stage's problem with every sample's limits and the goals of every CoarseStride()-th sample only, weighted by
  // the stride; rebuilt when the problem's blocks changed (limits joining, occlusion targets).
  ceres::Problem* StiffProblem();
  void FixChannels(ceres::Problem* problem);
  std::map<ceres::ResidualBlockId, int> block_sample_;
  // Samples per knot segment the coarse grid keeps at least.
  static constexpr double kCoarseSamplesPerSegment = 5;
  // The drone's and the lens's limits: penalties whose weight is ramped up over the solve (Solve). The
  // clearance is at full weight from the start: a soft stage must not let the path ring into the ground.
  static bool IsStiff(const std::string& term) {
    return term == "limits" || term == "keep_out" || term == "separation" || term == "out_of_shot";
  }
  // The objective's goals at a sample that the coarse grid of goals may weight (GoalWeightedSample): the
  // smooth ones. The depth of field is a hinge, zero where the actor is sharp, that binds sample by sample as a
  // limit does: on the grid alone the focus slipped off the walker between grid samples (the bundled sample's
  // draft objective 1,339.9 against 1,325.7), so it stays at every sample.
  static bool IsGoal(const std::string& term) { return term == "framing" || term == "background_blur"; }
  void AddTeamTerms(size_t k, double max_deviation_m);
  void AddClearanceTerm(const SampleBase& base, const Eigen::Vector3d& position, int shot, double max_deviation_m);
  void AddAdherenceTerms();

  const OptimizeInput& input_;
  const Trajectory& plan_;
  OptimizeOptions options_;
  std::shared_ptr<const SceneIndex> scene_;
  const PlanSamples* targets_;  // null: split_
  bool warm() const { return targets_ != nullptr; }
  PlanSamples split_;
  std::vector<ShotSettings> shots_;
  std::vector<Knot> knots_;
  std::vector<std::array<bool, kNumChannels>> touched_, held_;
  // Shared by every stiff block (the problem does not own it): a scale on their cost, ramped by Solve.
  std::unique_ptr<ceres::LossFunctionWrapper> stiffness_ =
      std::make_unique<ceres::LossFunctionWrapper>(nullptr, ceres::TAKE_OWNERSHIP);
  ceres::Problem problem_{ProblemOptions()};
  std::unique_ptr<ceres::Problem> coarse_;  // CoarseProblem: problem_'s cost functions, destroyed before it
  std::vector<std::unique_ptr<ceres::CostFunction>> stiff_costs_;  // stiff_'s weighted sample blocks
  std::unique_ptr<ceres::Problem> stiff_;                          // StiffProblem, destroyed before both
  int problem_generation_ = 0, stiff_generation_ = -1;             // blocks added to or removed from problem_
  // SolveBandedStage's solver, set up for one of the problems above at problem_generation_ banded_generation_
  // (destroyed before them).
  std::unique_ptr<BandedSolver> banded_;
  int banded_generation_ = -1;
  static ceres::Problem::Options ProblemOptions() {
    ceres::Problem::Options o;
    o.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    return o;
  }
  std::map<std::string, std::vector<ceres::ResidualBlockId>> terms_;  // the terms in blocks of their own
  std::map<std::string, std::vector<Part>> parts_;                    // the terms inside a sample's block
  SampleCostFunction* sample_block_ = nullptr;                        // the sample's block AddTerms builds
  double stiffness_scale_ = 1;  // the stiff parts' scale in the sample blocks, as stiffness_ (Solve)
  std::vector<ceres::ResidualBlockId> occlusion_blocks_;      // per sample, null when it has no target
  std::vector<std::unique_ptr<LimitsCost>> screened_limits_;  // limits not (yet) in the problem
  std::vector<int> screened_shot_;                            // the shot of each
  size_t unresolved_views_ = 0;
  size_t frames_without_target_ = 0;  // blocked, and no clear viewpoint within reach (summed over rounds)
  int iterations_ = 0;
  double solve_s_ = 0;
  double damping_ = 0;  // the banded solver's damping at the end of the last solve (0: none yet)
  std::string termination_ = "no variables";
  std::vector<std::string> skipped_;
};

void PlanOptimizer::ReadShots() {
  const std::string& source = input_.plan_source;
  for (size_t i = 0; i < plan_.shots.size(); ++i) {
    const ShotSpan& span = plan_.shots[i];
    const std::string where = source + ": shots[" + std::to_string(i) + "].intent";
    ShotSettings s;
    s.span = &span;
    for (const auto& h : span.intent.hold) {
      for (int c : ChannelsOf(h)) s.held.insert(c);
    }
    s.max_deviation_m = span.intent.max_deviation_m.value_or(options_.max_deviation_m);
    if (!span.subject.empty()) {
      // A hand-written plan may name a subject without giving its track: no framing for that shot.
      for (const auto& t : plan_.subjects) {
        if (t.name == span.subject) s.subject = &t;
      }
      if (!s.subject) {
        skipped_.push_back("framing and focus of shot \"" + span.name + "\": the plan has no track for subject \"" +
                           span.subject + "\"");
      }
    }
    for (const auto& name : span.intent.sharp) s.sharp.push_back(FindTrack(plan_, name, where + ".sharp"));
    // The focus mode as the plan records it; a plan written before it was recorded follows the subject
    // wherever the planned focus lies on it (below).
    s.focus_follows =
        s.subject && (span.intent.focus.empty() || span.intent.focus == "follow" || span.intent.focus == "rack");
    for (size_t r = 0; r < span.intent.rack.size(); ++r) {
      const RackIntent& rack = span.intent.rack[r];
      s.racks.emplace_back(rack, FindTrack(plan_, rack.subject, where + ".rack[" + std::to_string(r) + "].subject"));
    }
    s.background = span.intent.background_blur_px.has_value();
    if (s.background && s.sharp.empty()) {
      if (!s.subject) throw InputError(where + ".background_blur_px: the shot has no subject to keep sharp");
      s.sharp.push_back(s.subject);
    }
    shots_.push_back(s);
  }
}

// Which channels each knot may change: some sample using it has a term on the channel, and no sample
// using it belongs to a shot that holds it.
void PlanOptimizer::MarkFreeChannels() {
  knots_.assign(split_.num_knots, Knot{});
  touched_.assign(split_.num_knots, {});
  held_.assign(split_.num_knots, {});
  for (size_t k = 0; k < plan_.samples.size(); ++k) {
    const int first = split_.bases[k].knots.first_knot;
    const int shot = split_.shot_of_sample[k];
    std::array<bool, kNumChannels> touched{};
    for (int c : {kEast, kNorth, kUp, kYaw, kTilt}) touched[c] = true;  // limits, framing, clearance
    if (shot >= 0) {
      const ShotSettings& s = shots_[shot];
      const bool size_goal = s.span->intent.frame_height_fraction.has_value();
      // A prime lens or a fixed aperture (the small aircraft's built-in cameras) has nothing to move.
      const bool zooms = plan_.camera.max_focal_length_mm > plan_.camera.min_focal_length_mm;
      const bool stops = plan_.camera.max_f_number > plan_.camera.min_f_number;
      touched[kLogFocal] = zooms && (size_goal || !s.sharp.empty());
      touched[kStops] = stops && !s.sharp.empty();
      touched[kDioptre] = !s.sharp.empty() || s.focus_follows;  // DoF goals, or focus following
    }
    for (int j = 0; j < 4; ++j) {
      for (int c = 0; c < kNumChannels; ++c) {
        touched_[first + j][c] = touched_[first + j][c] || touched[c];
        if (shot >= 0 && shots_[shot].held.count(c)) held_[first + j][c] = true;
      }
    }
  }
}

void PlanOptimizer::AddTerms() {
  const CostWeights& w = options_.weights;
  const CameraSpec& camera = plan_.camera;
  const ImageExtentMm image = camera.image_extent_mm();
  const double coc_mm =
      camera.coc_mm > 0 ? camera.coc_mm : DefaultCocMm(camera.sensor_width_mm, camera.sensor_height_mm);
  static const Knot kZero{};
  const double* zero[4] = {kZero.data(), kZero.data(), kZero.data(), kZero.data()};

  const PlanSamples& targets = targets_ ? *targets_ : split_;
  for (size_t k = 0; k < plan_.samples.size(); ++k) {
    const SampleBase& base = split_.bases[k];
    const TrajectorySample& sample = plan_.samples[k];
    // Goals are aimed where the input put them (in a later stage of the ladder too).
    const SampleBase& target = targets.bases[k];
    const TrajectorySample& planned_sample = input_.plan.samples[k];
    const int shot = split_.shot_of_sample[k];
    const ShotSettings* s = shot >= 0 ? &shots_[shot] : nullptr;
    const bool moves = !(s && s->held.count(kEast) && s->held.count(kYaw));
    auto block = std::make_unique<SampleCostFunction>(base, &stiffness_scale_);
    sample_block_ = block.get();

    // Framing: keep the subject where the plan put it, at the size the shot asks for.
    if (s && s->subject && moves) {
      const Eigen::Vector3d aim = AimPoint(*s->subject, k);
      const SampleState<double> s0 = EvaluateSample(target, zero);
      const Framing<double> planned =
          MeasureFraming(target, s0, aim, s->subject->height_m, image.width_mm, image.height_mm);
      const Eigen::Vector3d in_camera = CameraPoint(target, s0, aim);
      if (in_camera.z() > 0.1 && std::fabs(planned.screen_x - 0.5) < 0.6 && std::fabs(planned.screen_y - 0.5) < 0.6) {
        auto* f = new FramingCost{
            base, aim,      s->subject->height_m, image.width_mm, image.height_mm, planned.screen_x, planned.screen_y,
            0.0,  w.framing};
        const ShotIntent& intent = s->span->intent;
        if (intent.frame_height_fraction) {
          const bool clamped = planned_sample.focal_length_mm <= camera.min_focal_length_mm + 1e-9 ||
                               planned_sample.focal_length_mm >= camera.max_focal_length_mm - 1e-9;
          if (!clamped) {
            f->target_fraction = planned.height_fraction;
          } else {
            const double span = s->span->end_time_s - s->span->start_time_s;
            const double u = span > 0 ? std::clamp((sample.time_s - s->span->start_time_s) / span, 0.0, 1.0) : 0.0;
            const double k0 = *intent.frame_height_fraction;
            const double k1 = intent.frame_height_fraction_end.value_or(k0);
            f->target_fraction = std::exp((1 - u) * std::log(k0) + u * std::log(k1));
          }
        }
        AddSampleTerm("framing", f, base, 3);
      }
    }

    // Depth of field: the sharp actors inside it, the background blurred enough; or the focus following
    // the subject when the camera may move and the shot asks nothing else of the lens.
    if (s && !s->sharp.empty()) {
      for (const SubjectTrack* t : s->sharp) {
        AddSampleTerm("depth_of_field", new SharpCost{base, AimPoint(*t, k), coc_mm * 1e-3, false, w.sharpness}, base,
                      1);
      }
      if (s->background) {
        const Eigen::Vector3d aim = AimPoint(*s->subject, k);
        double behind = s->span->intent.background_distance_m.value_or(std::numeric_limits<double>::infinity());
        if (scene_->full_caster) {
          const Eigen::Vector3d dir = (aim - planned_sample.position_enu_m).normalized();
          const auto hit = scene_->full_caster->Intersect(aim, dir, 0.5);
          behind = hit ? hit->distance_m : std::numeric_limits<double>::infinity();
        }
        auto* b = new BackgroundBlurCost{base,
                                         aim,
                                         behind,
                                         *s->span->intent.background_blur_px,
                                         camera.width_px / (camera.sensor_width_mm * 1e-3),
                                         w.background};
        AddSampleTerm("background_blur", b, base, 1);
      }
    } else if (const SubjectTrack* followed = s && s->focus_follows ? FollowedActor(*s, sample.time_s) : nullptr;
               followed && moves && !s->held.count(kDioptre)) {
      // Followed where the plan's focus lies on the actor: a focus the plan moved off it (a matched cut of a
      // team's edit, the lens's closest focus) is kept as planned.
      const Eigen::Vector3d aim = AimPoint(*followed, k);
      const double depth = CameraPoint(target, EvaluateSample(target, zero), aim).z();
      if (std::fabs(depth * target.dioptre - 1.0) < 1e-6) {
        AddSampleTerm("depth_of_field", new SharpCost{base, aim, coc_mm * 1e-3, true, w.sharpness}, base, 1);
      }
    }

    // Limits, keep-out, clearance.
    AddLimitsTerm(base, shot);
    const double max_dev = s ? s->max_deviation_m : options_.max_deviation_m;
    for (const auto& t : plan_.subjects) {
      const Eigen::Vector3d& foot = t.positions_enu_m[k];
      if ((sample.position_enu_m - foot).norm() > plan_.drone.min_subject_distance_m + max_dev + t.height_m + 1.0)
        continue;
      auto* keep_out =
          new KeepOutCost{base, foot, t.height_m, plan_.drone.min_subject_distance_m, options_.limit_margin, w.limits};
      AddConstraint(keep_out, base, shot, "subject_distance");
      AddSampleTerm("keep_out", keep_out, base, 1);
    }
    if (!input_.others.empty()) AddTeamTerms(k, max_dev);
    AddClearanceTerm(base, sample.position_enu_m, shot, max_dev);
    sample_block_ = nullptr;
    if (!block->empty()) AddResidual(block.release(), nullptr, base.knots.first_knot, static_cast<int>(k));
  }

  // Smoothness per spline segment, adherence per knot.
  for (const SampleGroup& g : split_.groups) {
    for (int seg = 0; seg < g.spline.num_segments(); ++seg) {
      auto* f = new SmoothnessCost{g.spline.segment_s(), w.smoothness};
      // Linear in the knots: its Jacobian, a constant, is taken once (optimizer/linear_cost_function.h).
      AddBlock("smoothness", new LinearCostFunction<SmoothnessCost, SmoothnessCost::kNumResiduals>(f),
               g.first_knot + seg);
    }
  }
  AddAdherenceTerms();

  FixChannels(&problem_);
}

// Fixed channels: held by a shot, or touched by no term.
void PlanOptimizer::FixChannels(ceres::Problem* problem) {
  for (size_t i = 0; i < knots_.size(); ++i) {
    std::vector<int> fixed;
    for (int c = 0; c < kNumChannels; ++c) {
      if (held_[i][c] || !touched_[i][c]) fixed.push_back(c);
    }
    if (static_cast<int>(fixed.size()) == kNumChannels) {
      problem->SetParameterBlockConstant(knots_[i].data());
    } else if (!fixed.empty()) {
      problem->SetManifold(knots_[i].data(), new ceres::SubsetManifold(kNumChannels, fixed));
    }
  }
}

// clearance: a sample within reach of the mesh (its margin plus the deviation allowed) keeps the margin.
void PlanOptimizer::AddClearanceTerm(const SampleBase& base, const Eigen::Vector3d& position, int shot,
                                     double max_deviation_m) {
  if (!scene_->surface || scene_->surface->num_faces() == 0) return;
  const auto closest = scene_->surface->Closest(position);
  if (!closest || closest->distance_m >= options_.clearance_margin_m + max_deviation_m + 0.5) return;
  auto owned = std::make_unique<ClearanceCost>(base, scene_->surface.get(),
                                               options_.clearance_margin_m * (1 + options_.limit_margin),
                                               options_.weights.clearance);
  ClearanceCost* clearance = owned.get();
  const int first = base.knots.first_knot;
  Constraint c;
  c.shot = shot;
  c.update = [this, clearance, first](bool reset) {
    return reset ? clearance->ResetShift() : clearance->UpdateShifts(KnotsFrom(first).data());
  };
  c.binding = [clearance](std::set<std::string>* names) {
    if (clearance->shift_m() > 0) names->insert("mesh_clearance");
  };
  c.margin = [this, b = &base, first](ceres::Problem* limits) {
    auto* margin =
        new ClearanceCost(*b, scene_->surface.get(), options_.clearance_margin_m * (1 + options_.limit_margin),
                          options_.weights.clearance);
    margin->SetSignedMargin();
    AddMarginRows(margin, {0}, first, limits);
  };
  constraints_.push_back(std::move(c));
  AddOneSampleTerm("clearance", std::move(owned), base);
}

// adherence per knot, with what is left of the deviation allowed at every sample the knot moves.
void PlanOptimizer::AddAdherenceTerms() {
  const CostWeights& w = options_.weights;
  std::vector<double> knot_deviation(knots_.size(), options_.max_deviation_m);
  std::vector<bool> seen(knots_.size(), false);
  std::vector<int> knot_shot(knots_.size(), -1);  // the shot of the last sample that moves with the knot
  for (size_t k = 0; k < plan_.samples.size(); ++k) {
    const int shot = split_.shot_of_sample[k];
    // What is left of the deviation allowed (a later stage starts where the cheaper one left the path).
    const double used = (plan_.samples[k].position_enu_m - input_.plan.samples[k].position_enu_m).norm();
    // Aimed at (1 - limit_margin) of it, as every other limit: a hinge met to within the solver's tolerance
    // then stays inside the deviation allowed.
    const double allowed = shot >= 0 ? shots_[shot].max_deviation_m : options_.max_deviation_m;
    const double dev = std::max(0.0, (1 - options_.limit_margin) * allowed - used);
    for (int j = 0; j < 4; ++j) {
      const int i = split_.bases[k].knots.first_knot + j;
      knot_deviation[i] = seen[i] ? std::min(knot_deviation[i], dev) : dev;
      seen[i] = true;
      knot_shot[i] = shot;
    }
  }
  for (size_t i = 0; i < knots_.size(); ++i) {
    auto* f = new AdherenceCost{knot_deviation[i], w.adherence, w.deviation, w.ridge};
    Constraint c;
    c.shot = knot_shot[i];
    c.update = [this, f, i](bool reset) {
      if (reset) return f->shift = 0.0;
      return f->UpdateShifts(knots_[i].data()) / std::max(f->max_deviation_m, 1.0);
    };
    c.binding = [f](std::set<std::string>* names) {
      if (f->shift > 0) names->insert("max_deviation");
    };
    c.margin = [this, f, i](ceres::Problem* limits) {
      limits->AddResidualBlock(
          new ceres::AutoDiffCostFunction<DeviationMargin, 1, kNumChannels>(new DeviationMargin{f->max_deviation_m}),
          nullptr, knots_[i].data());
    };
    adherence_.push_back(f);
    constraints_.push_back(std::move(c));
    terms_["adherence"].push_back(problem_.AddResidualBlock(
        new ceres::AutoDiffCostFunction<AdherenceCost, AdherenceCost::kNumResiduals, kNumChannels>(f), nullptr,
        knots_[i].data()));
  }
}

// Several drones: keep the separation from each other drone (a sphere about its fixed position, as the
// keep-out term does for actors), and stay out of its frame while its camera is live. Only samples within
// reach (the deviation allowed plus a metre) get a term.
void PlanOptimizer::AddTeamTerms(size_t k, double max_deviation_m) {
  const SampleBase& base = split_.bases[k];
  const Eigen::Vector3d& position = plan_.samples[k].position_enu_m;
  const double radius = plan_.drone.body_radius_m;
  for (const OtherDrone& other : input_.others) {
    const TrajectorySample& o = other.samples[k];
    const double separation = other.separation_m[k];
    if (separation > 0 && (position - o.position_enu_m).norm() < separation + max_deviation_m + 1.0) {
      auto* apart =
          new KeepOutCost{base, o.position_enu_m, 0.0, separation, options_.limit_margin, options_.weights.team};
      AddConstraint(apart, base, split_.shot_of_sample[k], "separation");
      AddSampleTerm("separation", apart, base, 1);
    }
    // This drone in the other's live frame (the other's camera held), and the other in this drone's.
    for (const bool this_views : {false, true}) {
      if (this_views ? !input_.own_live[k] : !other.live[k]) continue;
      const CameraSpec& camera = this_views ? plan_.camera : other.camera;
      const Eigen::Vector3d& viewer = this_views ? position : o.position_enu_m;
      const Eigen::Vector3d& body = this_views ? o.position_enu_m : position;
      const Eigen::Quaterniond& world_from_camera =
          this_views ? plan_.samples[k].world_from_camera : o.world_from_camera;
      const double focal_mm = this_views ? plan_.samples[k].focal_length_mm : o.focal_length_mm;
      const double body_radius = this_views ? other.body_radius_m : radius;
      const ImageExtentMm image = camera.image_extent_mm();
      const Eigen::Matrix3d camera_from_world = world_from_camera.conjugate().toRotationMatrix();
      const Eigen::Vector3d c = camera_from_world * (body - viewer);
      const double half_w = image.width_mm / (2 * focal_mm), half_h = image.height_mm / (2 * focal_mm);
      // Within reach: the deviation allowed, and for this drone's own camera the frame widening as it zooms.
      const double reach = body_radius + max_deviation_m + 1.0 + (this_views ? 0.5 * c.z() * half_w : 0.0);
      if (c.z() <= body_radius || std::fabs(c.x()) > half_w * c.z() + reach ||
          std::fabs(c.y()) > half_h * c.z() + reach) {
        continue;
      }
      auto* out = new OutOfShotCost{base,
                                    this_views,
                                    this_views ? body : viewer,
                                    camera_from_world,
                                    focal_mm,
                                    image.width_mm,
                                    image.height_mm,
                                    body_radius,
                                    options_.limit_margin,
                                    options_.weights.team};
      AddConstraint(out, base, split_.shot_of_sample[k], "out_of_shot");
      AddSampleTerm("out_of_shot", out, base, 1);
    }
  }
}

SampleState<double> PlanOptimizer::StateAt(const SampleBase& base) const {
  const double* k[4];
  for (int j = 0; j < 4; ++j) k[j] = knots_[base.knots.first_knot + j].data();
  return EvaluateSample(base, k);
}

// Occlusion: for every sample whose subject is hidden now and that has no target yet, the nearest
// viewpoint that sees it becomes a target.
// Occlusion: every sample whose subject is hidden now gets as target the nearest viewpoint that sees it
// (a sample still hidden after a round is re-targeted from where it got to). Returns how many targets
// were set.
size_t PlanOptimizer::AddVisibilityTargets() {
  if (!scene_->caster) return 0;
  occlusion_blocks_.resize(plan_.samples.size(), nullptr);
  size_t set = 0;
  for (size_t k = 0; k < plan_.samples.size(); ++k) {
    const int shot = split_.shot_of_sample[k];
    if (shot < 0 || !shots_[shot].subject || shots_[shot].held.count(kEast)) continue;
    const SampleBase& base = split_.bases[k];
    const Eigen::Vector3d camera = StateAt(base).position;
    const Eigen::Vector3d aim = AimPoint(*shots_[shot].subject, k);
    if (!LineOfSightBlocked(*scene_->caster, camera, aim)) continue;
    // Stay a quarter metre inside the deviation bound, whose hinge would otherwise hold the camera short.
    const double used = (plan_.samples[k].position_enu_m - input_.plan.samples[k].position_enu_m).norm();
    const double reach =
        std::max(0.0, shots_[shot].max_deviation_m - 0.25 - (camera - base.position_enu_m).norm() - used);
    const auto target = NearestClearViewpoint(*scene_->caster, scene_->surface.get(), camera, aim, reach,
                                              options_.clearance_margin_m, kTargetOvershootM);
    if (!target) {
      ++frames_without_target_;
      continue;
    }
    if (occlusion_blocks_[k]) {
      problem_.RemoveResidualBlock(occlusion_blocks_[k]);
      ++problem_generation_;
      auto& ids = terms_["occlusion"];
      ids.erase(std::find(ids.begin(), ids.end(), occlusion_blocks_[k]));
    }
    AddSampleTerm("occlusion", new ClearViewCost{base, *target, options_.weights.occlusion}, base, 3);
    occlusion_blocks_[k] = terms_["occlusion"].back();
    ++set;
  }
  return set;
}

void PlanOptimizer::Solve(bool ramp) {
  if (options_.constrained_solver) {
    SolveConstrained();
    return;
  }
  ceres::Solver::Options o;
  o.max_num_iterations = options_.max_iterations;
  o.function_tolerance = options_.function_tolerance;
  o.gradient_tolerance = 1e-12;
  o.parameter_tolerance = 1e-10;
  o.num_threads = 1;  // determinism: the same bytes at any thread count
  o.logging_type = std::getenv("CINEPATH_CERES_TRACE") ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  o.minimizer_progress_to_stdout = std::getenv("CINEPATH_CERES_TRACE") != nullptr;
  // Eigen's sparse Cholesky: SuiteSparse's supernodal factorization goes through a threaded BLAS, whose
  // sums depend on the machine's core count (the same plan gave other bytes on 1 and 2 cores).
  if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)) {
    o.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    o.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  } else {
    o.linear_solver_type = ceres::DENSE_QR;
  }
  // Continuation: the hard limits' penalties start soft and end at full weight (OptimizeOptions::ramp), each
  // stage starting where the last ended. A hinge that switches on mid-step makes the Gauss-Newton model
  // wrong and the step rejected; soft first, the path reaches the right region in a few long steps, and the
  // stiffer stages only tighten it.
  std::vector<double> stages = ramp ? options_.ramp : std::vector<double>{};
  if (stages.empty() || stages.back() != 1.0) stages.push_back(1.0);
  for (double scale : stages) {
    stiffness_->Reset(scale == 1.0 ? nullptr : new ceres::ScaledLoss(nullptr, scale, ceres::TAKE_OWNERSHIP),
                      ceres::TAKE_OWNERSHIP);
    stiffness_scale_ = scale;
    if (options_.external_solver) {
      std::vector<double*> blocks;
      std::vector<std::vector<int>> fixed;
      VariableBlocks(&blocks, &fixed);
      const auto start = std::chrono::steady_clock::now();
      iterations_ += options_.external_solver(&problem_, blocks, fixed);
      solve_s_ += Seconds(start);
      termination_ = "external solver";
      continue;
    }
    ceres::Problem* problem = scale < 1.0 ? CoarseProblem() : StiffProblem();
    if (!options_.ceres_solver) {
      SolveBandedStage(problem);
      continue;
    }
    ceres::Solver::Summary summary;
    ceres::Solve(o, problem, &summary);
    iterations_ += static_cast<int>(summary.iterations.size()) - 1;
    solve_s_ += summary.total_time_in_seconds;
    termination_ = summary.message;
    if (summary.termination_type == ceres::FAILURE) {
      throw RuntimeError("optimize: the solver failed: " + summary.message);
    }
  }
}

// One stage with the banded Levenberg-Marquardt (optimizer/banded_solver.h): the knots are one array, every
// block reads a few consecutive knots, and the fixed channels are those FixChannels holds.
void PlanOptimizer::SolveBandedStage(ceres::Problem* problem) {
  if (knots_.empty()) return;
  std::vector<std::array<bool, kNumChannels>> fixed(knots_.size());
  for (size_t i = 0; i < knots_.size(); ++i) {
    for (int c = 0; c < kNumChannels; ++c) fixed[i][c] = held_[i][c] || !touched_[i][c];
  }
  BandedSolverOptions o;
  o.max_iterations = options_.max_iterations;
  o.function_tolerance = options_.function_tolerance;
  // Each solve starts at the damping the last one ended with (the next stage or round is a nearby problem):
  // from Ceres' default of 1e-4, every solve first spent five to eight rejected steps raising it.
  if (damping_ > 0) o.initial_damping = damping_;
  const auto start = std::chrono::steady_clock::now();
  // The solver set up for this problem is kept while its blocks stay the same (the soft stages share the
  // coarse problem; the stiff solves share theirs until limits join).
  if (!banded_ || banded_generation_ != problem_generation_ ||
      !banded_->SetUpFor(problem, knots_.front().data(), fixed)) {
    banded_.reset();
    banded_ = std::make_unique<BandedSolver>(problem, knots_.front().data(), static_cast<int>(knots_.size()),
                                             std::move(fixed), o.max_chunks);
    banded_generation_ = problem_generation_;
  }
  const BandedSolverSummary summary = banded_->Solve(o);
  solve_s_ += Seconds(start);
  if (std::getenv("CINEPATH_CERES_TRACE"))
    std::fprintf(stderr, "stage at %g of the limits' weight: %d blocks, %d chunks, %d iterations, %.2f ms, %s\n",
                 stiffness_scale_, problem->NumResidualBlocks(), summary.chunks, summary.iterations,
                 1e3 * Seconds(start), summary.message.c_str());
  iterations_ += summary.iterations;
  damping_ = summary.final_damping;
  termination_ = summary.message;
  if (summary.failed) throw RuntimeError("optimize: the solver failed: " + summary.message);
}

int PlanOptimizer::CoarseStride() const {
  int segments = 0;
  for (const SampleGroup& g : split_.groups) segments += g.spline.num_segments();
  const double per_segment = static_cast<double>(plan_.samples.size()) / std::max(1, segments);
  return std::max(1, static_cast<int>(per_segment / kCoarseSamplesPerSegment));
}

ceres::Problem* PlanOptimizer::CoarseProblem() {
  const int stride = CoarseStride();
  if (stride == 1) return &problem_;
  if (coarse_) return coarse_.get();
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // problem_'s
  coarse_ = std::make_unique<ceres::Problem>(po);
  std::vector<ceres::ResidualBlockId> ids;
  problem_.GetResidualBlocks(&ids);  // in the order they were added
  for (const ceres::ResidualBlockId id : ids) {
    const auto found = block_sample_.find(id);  // (the adherence's blocks are per knot)
    const int sample = found == block_sample_.end() ? -1 : found->second;
    if (sample >= 0 && sample % stride != 0) continue;
    const ceres::LossFunction* loss = problem_.GetLossFunctionForResidualBlock(id);
    std::vector<double*> blocks;
    problem_.GetParameterBlocksForResidualBlock(id, &blocks);
    ceres::LossFunction* weighted =
        sample >= 0 ? new ceres::ScaledLoss(loss, stride, ceres::DO_NOT_TAKE_OWNERSHIP) : nullptr;
    coarse_->AddResidualBlock(const_cast<ceres::CostFunction*>(problem_.GetCostFunctionForResidualBlock(id)), weighted,
                              blocks);
  }
  FixChannels(coarse_.get());
  return coarse_.get();
}

ceres::Problem* PlanOptimizer::StiffProblem() {
  const int stride = CoarseStride();
  if (!options_.goals_on_coarse_grid || stride == 1) return &problem_;
  if (stiff_ && stiff_generation_ == problem_generation_) return stiff_.get();
  stiff_.reset();
  stiff_costs_.clear();
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // problem_'s, and stiff_costs_
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  stiff_ = std::make_unique<ceres::Problem>(po);
  std::vector<ceres::ResidualBlockId> ids;
  problem_.GetResidualBlocks(&ids);  // in the order they were added
  for (const ceres::ResidualBlockId id : ids) {
    const ceres::CostFunction* cost = problem_.GetCostFunctionForResidualBlock(id);
    std::vector<double*> blocks;
    problem_.GetParameterBlocksForResidualBlock(id, &blocks);
    const auto* sample_block = dynamic_cast<const SampleCostFunction*>(cost);
    const auto found = block_sample_.find(id);
    const int sample = found == block_sample_.end() ? -1 : found->second;
    if (!sample_block || sample < 0) {  // segments, knots, limits that joined later, occlusion targets
      stiff_->AddResidualBlock(const_cast<ceres::CostFunction*>(cost),
                               const_cast<ceres::LossFunction*>(problem_.GetLossFunctionForResidualBlock(id)), blocks);
      continue;
    }
    const bool on_grid = sample % stride == 0;
    if (!on_grid && !sample_block->has_limits()) continue;
    stiff_costs_.push_back(std::make_unique<GoalWeightedSample>(sample_block, on_grid ? stride : 0.0));
    stiff_->AddResidualBlock(stiff_costs_.back().get(), nullptr, blocks);
  }
  FixChannels(stiff_.get());
  stiff_generation_ = problem_generation_;
  return stiff_.get();
}

void PlanOptimizer::VariableBlocks(std::vector<double*>* blocks, std::vector<std::vector<int>>* fixed) {
  for (size_t i = 0; i < knots_.size(); ++i) {
    if (problem_.IsParameterBlockConstant(knots_[i].data())) continue;
    blocks->push_back(knots_[i].data());
    fixed->emplace_back();
    for (int c = 0; c < kNumChannels; ++c) {
      if (held_[i][c] || !touched_[i][c]) fixed->back().push_back(c);
    }
  }
}

void PlanOptimizer::AddMarginRows(ceres::CostFunction* margins, std::vector<int> rows, int first_knot,
                                  ceres::Problem* limits) const {
  std::unique_ptr<ceres::CostFunction> owned(margins);
  const std::array<const double*, 4> knots = KnotsFrom(first_knot);
  std::vector<double> now(margins->num_residuals());
  if (!margins->Evaluate(knots.data(), now.data(), nullptr)) return;
  rows.erase(std::remove_if(rows.begin(), rows.end(), [&](int i) { return !std::isfinite(now[i]); }), rows.end());
  if (rows.empty()) return;
  std::vector<double*> blocks;
  for (const double* k : knots) blocks.push_back(const_cast<double*>(k));
  limits->AddResidualBlock(new MarginRows(owned.release(), std::move(rows)), nullptr, blocks);
}

void PlanOptimizer::SolveConstrained() {
  std::vector<std::unique_ptr<ceres::CostFunction>> pulls;  // the adherence without its deviation hinge
  ceres::Problem::Options shared;
  shared.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // problem_'s, and `pulls`
  ceres::Problem goals(shared), limits;
  for (Knot& k : knots_) {
    goals.AddParameterBlock(k.data(), kNumChannels);
    limits.AddParameterBlock(k.data(), kNumChannels);
  }
  for (const auto& [name, ids] : terms_) {
    if (IsStiff(name) || name == "clearance" || name == "adherence") continue;
    for (const ceres::ResidualBlockId id : ids) {
      std::vector<double*> blocks;
      problem_.GetParameterBlocksForResidualBlock(id, &blocks);
      goals.AddResidualBlock(const_cast<ceres::CostFunction*>(problem_.GetCostFunctionForResidualBlock(id)), nullptr,
                             blocks);
    }
  }
  for (size_t i = 0; i < knots_.size(); ++i) {
    auto* pull = new AdherenceCost(*adherence_[i]);
    pull->deviation_weight = 0;  // the deviation allowed is a constraint
    pulls.emplace_back(
        new ceres::AutoDiffCostFunction<AdherenceCost, AdherenceCost::kNumResiduals, kNumChannels>(pull));
    goals.AddResidualBlock(pulls.back().get(), nullptr, knots_[i].data());
  }
  for (const Constraint& c : constraints_) c.margin(&limits);
  for (const auto& screened : screened_limits_) {
    if (screened) AddMargin(*screened, screened->base.knots.first_knot, &limits);
  }
  FixChannels(&goals);
  FixChannels(&limits);
  ConstrainedProblem problem;
  problem.goals = &goals;
  problem.limits = &limits;
  VariableBlocks(&problem.blocks, &problem.fixed_channels);
  const auto start = std::chrono::steady_clock::now();
  iterations_ += options_.constrained_solver(problem);
  solve_s_ += Seconds(start);
  termination_ = "constrained solver";
}

// Rule 1 (docs/optimize.md, "Limits as constraints"): the penalties alone leave a limit broken wherever
// the goals pull harder than its weight; the augmented Lagrangian's multipliers, carried as shifts inside
// the hinges, grow where a limit is broken until the solve meets it, without a larger weight.
void PlanOptimizer::SolveUntilTheLimitsHold() {
  for (int round = 0; round < options_.multiplier_rounds; ++round) {
    if (UpdateMultipliers() <= kConstraintTolerance) return;
    Solve(false);
    while (AddLimitsNearTheirBounds() > 0) Solve(false);
  }
}

double PlanOptimizer::UpdateMultipliers() {
  double most = 0;
  for (auto& c : constraints_) most = std::max(most, c.update(false));
  return most;
}

void PlanOptimizer::ResetMultipliers() {
  binding_.assign(shots_.size(), {});
  for (auto& c : constraints_) {
    if (c.shot >= 0) c.binding(&binding_[c.shot]);
    c.update(true);
  }
}

// A sample whose every limit holds with room to spare has a zero limits residual, and so does every change
// that keeps it so: it joins the problem only when a solve brings it near a limit (AddLimitsNearTheirBounds).
void PlanOptimizer::AddLimitsTerm(const SampleBase& base, int shot) {
  static const Knot kZero{};
  const double* zero[4] = {kZero.data(), kZero.data(), kZero.data(), kZero.data()};
  terms_["limits"];  // reported even when every sample's limits are left out
  auto limits = std::make_unique<LimitsCost>(LimitsCost{base, plan_.drone, plan_.camera, scene_->takeoff_up_m,
                                                        options_.limit_margin, options_.weights.limits});
  limits->free = FreeChannels(base);
  if (limits->Headroom(zero, limits->free) > -kLimitScreen) {
    AddConstraint(limits.get(), base, shot, "");
    AddSampleTerm("limits", limits.release(), base, LimitsCost::kNumResiduals);
  } else {
    screened_limits_.push_back(std::move(limits));
    screened_shot_.push_back(shot);
  }
}

std::array<const double*, 4> PlanOptimizer::KnotsOf(const SampleBase& base) const {
  return KnotsFrom(base.knots.first_knot);
}

std::array<const double*, 4> PlanOptimizer::KnotsFrom(int first) const {
  return {knots_[first].data(), knots_[first + 1].data(), knots_[first + 2].data(), knots_[first + 3].data()};
}

std::array<bool, kNumChannels> PlanOptimizer::FreeChannels(const SampleBase& base) const {
  std::array<bool, kNumChannels> free{};
  for (int j = 0; j < 4; ++j) {
    const int i = base.knots.first_knot + j;
    for (int c = 0; c < kNumChannels; ++c) free[c] = free[c] || (touched_[i][c] && !held_[i][c]);
  }
  free[kEast] = free[kEast] || free[kNorth] || free[kUp];
  return free;
}

double PlanOptimizer::ScreenedLimitsCost() const {
  double cost = 0;
  for (const auto& limits : screened_limits_) {
    if (!limits) continue;
    cost += limits->Cost(KnotsOf(limits->base).data());
  }
  return cost;
}

size_t PlanOptimizer::AddLimitsNearTheirBounds() {
  size_t added = 0;
  for (size_t i = 0; i < screened_limits_.size(); ++i) {
    std::unique_ptr<LimitsCost>& limits = screened_limits_[i];
    if (!limits) continue;
    if (limits->Headroom(KnotsOf(limits->base).data(), limits->free) <= -kLimitRecheck) continue;
    const SampleBase base = limits->base;
    AddConstraint(limits.get(), base, screened_shot_[i], "");
    AddSampleTerm("limits", limits.release(), base, LimitsCost::kNumResiduals);
    ++added;
  }
  return added;
}

double PlanOptimizer::BlocksCost(const std::vector<ceres::ResidualBlockId>& ids) {
  if (ids.empty()) return 0;  // (an empty list would evaluate every block)
  ceres::Problem::EvaluateOptions eo;
  eo.residual_blocks = ids;
  eo.num_threads = 1;
  double cost = 0;
  problem_.Evaluate(eo, &cost, nullptr, nullptr, nullptr);
  return cost;
}

double PlanOptimizer::PartsCost(const std::vector<Part>& parts) const {
  double cost = 0, r[LimitsCost::kNumResiduals];
  for (const Part& p : parts) {
    if (!p.cost->Evaluate(KnotsFrom(p.first_knot).data(), r, nullptr)) continue;
    double squares = 0;
    for (int i = 0; i < p.cost->num_residuals(); ++i) squares += r[i] * r[i];
    cost += 0.5 * squares;
  }
  return cost;
}

std::set<std::string> PlanOptimizer::TermNames() const {
  std::set<std::string> names;
  for (const auto& [name, ids] : terms_) names.insert(name);
  for (const auto& [name, parts] : parts_) names.insert(name);
  return names;
}

Json PlanOptimizer::TermCosts(double* total) {
  Json out = Json::object();
  *total = 0;
  for (const std::string& name : TermNames()) {
    double cost = name == "limits" ? ScreenedLimitsCost() : 0.0;
    if (const auto parts = parts_.find(name); parts != parts_.end()) cost += PartsCost(parts->second);
    if (const auto ids = terms_.find(name); ids != terms_.end()) cost += BlocksCost(ids->second);
    out[name] = RoundToDecimals(cost, 9);
    *total += cost;
  }
  return out;
}

Trajectory PlanOptimizer::Apply(const std::vector<double>& group_alpha) const {
  Trajectory out = plan_;
  std::optional<EnuFrame> frame;
  if (out.origin) frame.emplace(*out.origin);
  const ImageExtentMm image = out.camera.image_extent_mm();
  // The state at `alpha`: positions along the straight line from the input's (a refit group's base is not
  // the input), every other channel a multiple of its change.
  const auto scaled = [&](const SampleBase& base, const Eigen::Vector3d& input_position, double alpha) {
    SampleState<double> s = StateAt(base);
    if (alpha == 1.0) return s;
    s.position = input_position + alpha * (s.position - input_position);
    s.yaw *= alpha;
    s.tilt *= alpha;
    s.log_focal *= alpha;
    s.dioptre = base.dioptre + alpha * (s.dioptre - base.dioptre);
    s.stops *= alpha;
    return s;
  };
  const auto apply = [&](const SampleBase& base, const SampleState<double>& s, Eigen::Vector3d* position,
                         Eigen::Quaterniond* world_from_camera, double* focal_mm, double* focus_m, double* f_number) {
    *position = s.position;
    if (s.yaw != 0 || s.tilt != 0) *world_from_camera = ChangedWorldFromCamera(base, s.yaw, s.tilt).normalized();
    *focal_mm = FocalLengthMm(base, s);
    if (s.dioptre != base.dioptre)
      *focus_m = s.dioptre > 1e-12 ? 1.0 / s.dioptre : std::numeric_limits<double>::infinity();
    *f_number = FNumber(base, s);
  };
  for (size_t k = 0; k < out.samples.size(); ++k) {
    TrajectorySample& sample = out.samples[k];
    const SampleBase& base = split_.bases[k];
    const SampleState<double> s = scaled(base, plan_.samples[k].position_enu_m, group_alpha[split_.group_of_sample[k]]);
    const bool moved = s.yaw != 0 || s.tilt != 0 || s.log_focal != 0 || s.position != plan_.samples[k].position_enu_m;
    apply(base, s, &sample.position_enu_m, &sample.world_from_camera, &sample.focal_length_mm, &sample.focus_distance_m,
          &sample.f_number);
    const bool turned = s.yaw != 0 || s.tilt != 0, displaced = s.position != plan_.samples[k].position_enu_m;
    if (turned || (frame && displaced)) {
      // Against true north and the local vertical where the camera now is, and its lat/lon/h there
      // (core/local_level.h); a nose off the camera keeps its heading when only the position moved.
      const bool nose_on_camera = turned || sample.gimbal_yaw_deg == 0;
      SetLocalAngles(frame ? &*frame : nullptr, sample,
                     nose_on_camera ? std::numeric_limits<double>::quiet_NaN() : sample.drone_heading_deg);
    }
    if (moved) {
      sample.subjects_in_frame.clear();
      const Eigen::Quaterniond camera_from_world = sample.world_from_camera.conjugate();
      for (const auto& t : out.subjects) {
        const Eigen::Vector3d c = camera_from_world * (AimPoint(t, k) - sample.position_enu_m);
        if (c.z() > 1e-9 && std::fabs(c.x() / c.z()) <= image.width_mm / (2.0 * sample.focal_length_mm) &&
            std::fabs(c.y() / c.z()) <= image.height_mm / (2.0 * sample.focal_length_mm)) {
          sample.subjects_in_frame.push_back(t.name);
        }
      }
    }
  }
  // Keyframes follow the change at their own times (in their shot's group).
  for (Keyframe& key : out.keyframes) {
    size_t k = 0;
    while (k < out.samples.size() &&
           !(plan_.samples[k].shot == key.shot && plan_.samples[k].time_s >= key.time_s - 1e-9))
      ++k;
    if (k == out.samples.size()) continue;
    const int group = split_.group_of_sample[k];
    const SampleGroup& g = split_.groups[group];
    SampleBase base;
    base.knots = g.spline.At(key.time_s);
    base.knots.first_knot += g.first_knot;
    base.position_enu_m = key.position_enu_m;
    base.world_from_camera = key.world_from_camera.normalized();
    base.focal_length_mm = key.focal_length_mm;
    base.dioptre = std::isinf(key.focus_distance_m) ? 0.0 : 1.0 / key.focus_distance_m;
    base.f_number = key.f_number;
    apply(base, scaled(base, key.position_enu_m, group_alpha[group]), &key.position_enu_m, &key.world_from_camera,
          &key.focal_length_mm, &key.focus_distance_m, &key.f_number);
  }
  std::unique_ptr<scene::CasterGround> ground;
  if (scene_->caster) ground = std::make_unique<scene::CasterGround>(*scene_->caster, input_.scene_source);
  out.feasibility = CheckFeasibility(out, split_.cut_before, {}, ground.get());
  return out;
}

double PlanOptimizer::BlockedFraction(const Trajectory& plan, size_t* first_blocked) const {
  size_t blocked = 0, checked = 0;
  *first_blocked = plan.samples.size();
  if (!scene_->caster) return 0;
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    const int shot = split_.shot_of_sample[k];
    if (shot < 0 || !shots_[shot].subject) continue;
    ++checked;
    if (LineOfSightBlocked(*scene_->caster, plan.samples[k].position_enu_m, AimPoint(*shots_[shot].subject, k))) {
      ++blocked;
      *first_blocked = std::min(*first_blocked, k);
    }
  }
  return checked ? static_cast<double>(blocked) / checked : 0.0;
}

Json PlanOptimizer::Report(const Trajectory& optimized, const Json& before_terms, const Json& after_terms,
                           double total_before, double total_after) const {
  Json report = Json::object();
  report["format"] = "cinepath.optimize-report";
  report["version"] = 1;
  report["plan"] = std::filesystem::path(input_.plan_source).filename().string();
  report["scene"] = input_.mesh ? Json(input_.scene_source) : Json(nullptr);
  report["quality"] = QualityName(options_.quality);
  report["knot_spacing_s"] = options_.knot_spacing_s;
  Json terms = Json::object();
  for (const auto& [name, value] : before_terms.items()) {
    Json t = Json::object();
    t["before"] = value;
    t["after"] = after_terms[name];
    terms[name] = t;
  }
  report["terms"] = terms;
  Json total = Json::object();
  total["before"] = RoundToDecimals(total_before, 9);
  total["after"] = RoundToDecimals(total_after, 9);
  report["total"] = total;

  // The worst violation of every limit, before and after.
  const auto worst = [](const FeasibilityReport& r) {
    std::map<std::string, const FeasibilityViolation*> w;
    for (const auto& v : r.violations) {
      auto& slot = w[v.limit];
      if (!slot || std::fabs(v.worst_value - v.limit_value) > std::fabs(slot->worst_value - slot->limit_value))
        slot = &v;
    }
    return w;
  };
  std::unique_ptr<scene::CasterGround> ground;
  if (scene_->caster) ground = std::make_unique<scene::CasterGround>(*scene_->caster, input_.scene_source);
  const FeasibilityReport before = CheckFeasibility(input_.plan, split_.cut_before, {}, ground.get());
  const auto wb = worst(before), wa = worst(optimized.feasibility);
  std::set<std::string> names;
  for (const auto& [n, v] : wb) names.insert(n);
  for (const auto& [n, v] : wa) names.insert(n);
  Json limits = Json::object();
  for (const auto& n : names) {
    Json l = Json::object();
    const FeasibilityViolation* any = wb.count(n) ? wb.at(n) : wa.at(n);
    l["limit"] = RoundToDecimals(any->limit_value, 6);
    l["unit"] = any->unit;
    l["before"] = wb.count(n) ? Json(RoundToDecimals(wb.at(n)->worst_value, 6)) : Json(nullptr);
    l["after"] = wa.count(n) ? Json(RoundToDecimals(wa.at(n)->worst_value, 6)) : Json(nullptr);
    limits[n] = l;
  }
  report["limits"] = limits;
  report["feasible_before"] = before.feasible();
  report["feasible_after"] = optimized.feasibility.feasible();

  // Deviation from the planned path.
  double max_dev = 0;
  for (size_t k = 0; k < input_.plan.samples.size(); ++k) {
    max_dev = std::max(max_dev, (optimized.samples[k].position_enu_m - input_.plan.samples[k].position_enu_m).norm());
  }
  report["max_deviation_m"] = RoundToDecimals(max_dev, 6);

  // The scene: clearance and lines of sight, before and after.
  if (scene_->surface) {
    const auto min_clearance = [&](const Trajectory& p) {
      double m = std::numeric_limits<double>::infinity();
      for (const auto& s : p.samples) {
        if (const auto c = scene_->surface->Closest(s.position_enu_m)) m = std::min(m, c->distance_m);
      }
      return std::isinf(m) ? Json(nullptr) : Json(RoundToDecimals(m, 6));
    };
    Json c = Json::object();
    c["margin_m"] = options_.clearance_margin_m;
    c["min_before_m"] = min_clearance(input_.plan);
    c["min_after_m"] = min_clearance(optimized);
    c["faces_in_scene"] = scene_->faces_in_scene;
    c["faces_indexed"] = scene_->corridor.num_faces();
    c["index_s"] = RoundToDecimals(scene_->build_s, 4);
    report["clearance"] = c;
    size_t first_b = 0, first_a = 0;
    Json o = Json::object();
    o["blocked_fraction_before"] = RoundToDecimals(BlockedFraction(input_.plan, &first_b), 6);
    o["blocked_fraction_after"] = RoundToDecimals(BlockedFraction(optimized, &first_a), 6);
    o["first_blocked_time_s"] =
        first_a < optimized.samples.size() ? Json(optimized.samples[first_a].time_s) : Json(nullptr);
    o["frames_without_clear_view"] = unresolved_views_;
    o["frames_given_a_target"] = terms_.count("occlusion") ? terms_.at("occlusion").size() : 0;
    o["searches_without_target"] = frames_without_target_;
    report["occlusion"] = o;
  }

  // Per shot: the subject's blur and the background's, after.
  const CameraSpec& camera = plan_.camera;
  Json shots = Json::array();
  for (size_t i = 0; i < shots_.size(); ++i) {
    const ShotSettings& s = shots_[i];
    Json j = Json::object();
    j["name"] = s.span->name;
    double subject_blur = 0, background_blur = std::numeric_limits<double>::infinity();
    bool any = false;
    for (size_t k = 0; k < optimized.samples.size(); ++k) {
      if (split_.shot_of_sample[k] != static_cast<int>(i) || !s.subject) continue;
      const TrajectorySample& t = optimized.samples[k];
      const Eigen::Vector3d aim = AimPoint(*s.subject, k);
      const double depth = (t.world_from_camera.conjugate() * (aim - t.position_enu_m)).z();
      if (depth <= t.focal_length_mm * 1e-3) continue;
      any = true;
      const double px = camera.width_px / camera.sensor_width_mm;
      subject_blur =
          std::max(subject_blur, BlurCircleMm(t.focal_length_mm, t.f_number, t.focus_distance_m, depth) * px);
      if (s.background) {
        double behind = s.span->intent.background_distance_m.value_or(std::numeric_limits<double>::infinity());
        if (scene_->full_caster) {
          const auto hit = scene_->full_caster->Intersect(aim, (aim - t.position_enu_m).normalized(), 0.5);
          behind = hit ? hit->distance_m : std::numeric_limits<double>::infinity();
        }
        const double d = depth + behind;
        const double blur = std::isinf(d) ? BlurCircleMm(t.focal_length_mm, t.f_number, t.focus_distance_m, 1e12)
                                          : BlurCircleMm(t.focal_length_mm, t.f_number, t.focus_distance_m, d);
        background_blur = std::min(background_blur, blur * px);
      }
    }
    // What held the shot's goals back: the limits whose multiplier the solve needed (docs/optimize.md,
    // "Limits as constraints"); a goal missed while this is empty gave way to the weights, not to a limit.
    Json binding = Json::array();
    if (i < binding_.size()) {
      for (const std::string& name : binding_[i]) binding.push_back(name);
    }
    j["binding_limits"] = binding;
    j["subject_blur_px_max"] = any ? Json(RoundToDecimals(subject_blur, 4)) : Json(nullptr);
    if (s.background) {
      j["background_blur_px_goal"] = *s.span->intent.background_blur_px;
      j["background_blur_px_min"] = any ? Json(RoundToDecimals(background_blur, 4)) : Json(nullptr);
    }
    shots.push_back(j);
  }
  report["shots"] = shots;

  Json solver = Json::object();
  solver["iterations"] = iterations_;
  solver["time_s"] = RoundToDecimals(solve_s_, 4);
  solver["stopped"] = termination_;
  solver["variables"] = problem_.NumParameters();
  solver["residuals"] = problem_.NumResiduals();
  report["solver"] = solver;
  report["skipped"] = skipped_;
  return report;
}

GuardSetup PlanOptimizer::GuardSetupFor() const {
  GuardSetup g;
  g.cut_before = split_.cut_before;
  g.shot_of_sample = split_.shot_of_sample;
  const size_t n = plan_.samples.size();
  g.max_deviation_m.assign(n, options_.max_deviation_m);
  for (const auto& sample : input_.plan.samples) g.origin_enu_m.push_back(sample.position_enu_m);
  g.aim_enu_m.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const int shot = split_.shot_of_sample[k];
    if (shot < 0) continue;
    g.max_deviation_m[k] = shots_[shot].max_deviation_m;
    if (shots_[shot].subject) g.aim_enu_m[k] = AimPoint(*shots_[shot].subject, k);
  }
  g.caster = scene_->caster.get();
  g.surface = scene_->surface.get();
  g.clearance_margin_m = options_.clearance_margin_m;
  g.scene_source = input_.scene_source;
  return g;
}

void PlanOptimizer::Prepare() {
  split_ = SplitPlan(plan_, options_.knot_spacing_s, input_.plan_source, !warm());
  ReadShots();
  if (!input_.mesh) {
    skipped_.push_back("clearance: no scene mesh");
    skipped_.push_back("occlusion: no scene mesh");
  }
  MarkFreeChannels();
  AddTerms();
}

double PlanOptimizer::GoalCost() {
  static const std::set<std::string> kRegularizers = {"smoothness", "adherence", "occlusion"};
  std::vector<ceres::ResidualBlockId> ids;
  for (const auto& [name, blocks] : terms_) {
    if (!kRegularizers.count(name)) ids.insert(ids.end(), blocks.begin(), blocks.end());
  }
  double cost = 0;
  for (const auto& [name, parts] : parts_) {
    if (!kRegularizers.count(name)) cost += PartsCost(parts);
  }
  return cost + BlocksCost(ids) + ScreenedLimitsCost();
}

double PlanOptimizer::Objective() {
  Prepare();
  return GoalCost();
}

void PlanOptimizer::ScaleKnots(const std::vector<double>& alpha) {
  for (size_t g = 0; g < split_.groups.size(); ++g) {
    const SampleGroup& group = split_.groups[g];
    for (int i = 0; i < group.spline.num_knots(); ++i) {
      for (double& v : knots_[group.first_knot + i]) v *= alpha[g];
    }
  }
}

double PlanOptimizer::ObjectiveAt(const std::vector<double>& alpha) {
  const std::vector<Knot> solution = knots_;
  ScaleKnots(alpha);
  const double cost = GoalCost();
  knots_ = solution;  // a copy into the same storage
  return cost;
}

Json PlanOptimizer::RetryAtFullWeight(const LimitGuard& guard, GuardedPlan* kept) {
  if (kept->alpha == 1.0 || warm() || options_.constrained_solver || options_.external_solver) return nullptr;
  const std::vector<Knot> first = knots_;
  const std::vector<std::set<std::string>> first_binding = binding_;
  const double first_objective = ObjectiveAt(kept->group_alpha);
  for (auto& k : knots_) k.fill(0.0);
  Solve(false);
  while (AddLimitsNearTheirBounds() > 0) Solve(false);
  SolveUntilTheLimitsHold();
  ResetMultipliers();
  GuardedPlan second = Guarded(guard);
  const double second_objective = ObjectiveAt(second.group_alpha);
  const bool better = second_objective < first_objective;
  Json r = Json::object();
  r["first_alpha"] = kept->alpha;
  r["first_objective"] = RoundToDecimals(first_objective, 6);
  r["retry_alpha"] = second.alpha;
  r["retry_objective"] = RoundToDecimals(second_objective, 6);
  r["kept"] = better ? "retry" : "first";
  if (better) {
    *kept = std::move(second);
  } else {
    knots_ = first;
    binding_ = first_binding;
  }
  return r;
}

OptimizeResult PlanOptimizer::Run() {
  Prepare();
  AddVisibilityTargets();
  // Later rounds re-target the frames still hidden and re-solve from where the last round ended, at full
  // weight. A stage that starts from a cheaper preset's result is at full weight from the start: the soft
  // stages exist to reach the right region, and it starts there.
  for (int round = 0; round < std::max(1, options_.visibility_rounds); ++round) {
    if (round > 0 && AddVisibilityTargets() == 0) break;
    Solve(round == 0 && !warm());
    if (options_.constrained_solver) continue;  // the peer has every limit as a constraint already
    while (AddLimitsNearTheirBounds() > 0) Solve(false);
    SolveUntilTheLimitsHold();
  }
  if (terms_.count("occlusion") && terms_["occlusion"].empty()) terms_.erase("occlusion");
  ResetMultipliers();  // costs are reported as the plain penalties, whatever the multipliers came to

  // Rule 2: the solver's output only if it is never worse than the input in any limit, else the largest
  // fraction of its change that is (optimizer/limit_guard.h).
  const LimitGuard guard(plan_, GuardSetupFor());
  GuardedPlan kept = Guarded(guard);
  const Json retry = RetryAtFullWeight(guard, &kept);

  // Costs before (every knot at zero: the plan as given) and after (the change kept; where a group was
  // refit, alpha times its change about the refit path).
  const std::vector<Knot> solution = knots_;
  for (auto& k : knots_) k.fill(0.0);
  double total_before = 0, total_after = 0;
  const Json before = TermCosts(&total_before);
  knots_ = solution;
  ScaleKnots(kept.group_alpha);
  const Json after = TermCosts(&total_after);

  OptimizeResult result;
  result.plan = std::move(kept.plan);
  for (const auto& series : kept.measure) {  // frames still hidden
    if (series.limit == "line_of_sight")
      unresolved_views_ = std::count(series.values.begin(), series.values.end(), 1.0);
  }
  result.report = Report(result.plan, before, after, total_before, total_after);
  Json g = Json::object();
  g["alpha"] = kept.alpha;
  if (kept.group_alpha.size() > 1) g["group_alpha"] = kept.group_alpha;
  g["raw_broke"] = kept.raw_broke;
  g["still_broken"] = StillBroken(kept.measure, result.plan, &result.failure);
  if (!retry.is_null()) g["retry"] = retry;
  result.report["guard"] = g;

  Json record = Json::object();
  record["by"] = "cinepath optimize";
  record["quality"] = QualityName(options_.quality);
  record["knot_spacing_s"] = options_.knot_spacing_s;
  record["scene"] = input_.mesh ? Json(input_.scene_source) : Json(nullptr);
  Json names = Json::array();
  for (const std::string& name : TermNames()) names.push_back(name);
  record["terms"] = names;
  record["cost_before"] = RoundToDecimals(total_before, 9);
  record["cost_after"] = RoundToDecimals(total_after, 9);
  record["iterations"] = iterations_;
  result.plan.optimized = record;

  return result;
}

// Rule 4, the quality ladder (docs/optimize.md): a preset runs the cheaper presets first and starts from
// the result the last of them kept; it keeps its own result only when the objective (the goal and limit
// terms of the result, one function of the plan whatever the preset) is no larger. Its guard holds it
// never worse in any limit than the result it started from. So final <= standard <= draft in objective,
// and no preset breaks a limit more than a cheaper one does, by construction.
OptimizeResult RunLadder(const OptimizeInput& input, const OptimizeOptions& options,
                         const std::shared_ptr<const SceneIndex>& scene) {
  std::vector<Quality> ladder = {Quality::kDraft};
  if (options.quality != Quality::kDraft) ladder.push_back(Quality::kStandard);
  if (options.quality == Quality::kFinal) ladder.push_back(Quality::kFinal);
  std::optional<PlanSamples> targets;  // the first stage's samples: where every stage aims the goals
  OptimizeResult kept;
  double kept_objective = 0;
  Json first_report, stages = Json::array();
  int iterations = 0;
  double solve_s = 0;
  for (size_t i = 0; i < ladder.size(); ++i) {
    OptimizeOptions stage_options = options;  // the preset asked for, as given (its knobs too)
    if (i + 1 < ladder.size()) {
      const OptimizeOptions preset = OptimizeOptions::ForQuality(ladder[i]);
      stage_options.quality = preset.quality;
      stage_options.knot_spacing_s = preset.knot_spacing_s;
      stage_options.max_iterations = preset.max_iterations;
      stage_options.function_tolerance = preset.function_tolerance;
      stage_options.visibility_rounds = preset.visibility_rounds;
      stage_options.multiplier_rounds = preset.multiplier_rounds;
      stage_options.goals_on_coarse_grid = preset.goals_on_coarse_grid;
    }
    OptimizeResult result;
    {
      PlanOptimizer stage(input, i == 0 ? input.plan : kept.plan, stage_options, scene, targets ? &*targets : nullptr);
      result = stage.Run();
      if (i == 0) targets = stage.samples();
    }  // its problem freed before the judge builds one: the judge's reuses its memory, whose pages are in
       // (the commands keep freed memory, core/heap_pages.h)
    PlanOptimizer judge(input, result.plan, stage_options, scene, &*targets);
    const double objective = judge.Objective();
    iterations += result.report["solver"]["iterations"].get<int>();
    solve_s += result.report["solver"]["time_s"].get<double>();
    const bool keep = i == 0 || objective <= kept_objective;
    Json entry = Json::object();
    entry["quality"] = QualityName(ladder[i]);
    entry["objective"] = RoundToDecimals(objective, 9);
    entry["alpha"] = result.report["guard"]["alpha"];
    entry["kept"] = keep;
    stages.push_back(entry);
    if (i == 0) first_report = result.report;
    if (!keep) continue;
    kept = std::move(result);
    kept_objective = objective;
  }
  // The report of the result kept, its costs before taken on the plan as given, the ladder and the work
  // of every stage.
  Json& report = kept.report;
  report["quality"] = QualityName(options.quality);
  for (auto& [name, term] : report["terms"].items()) {
    if (first_report["terms"].contains(name)) term["before"] = first_report["terms"][name]["before"];
  }
  report["total"]["before"] = first_report["total"]["before"];
  report["solver"]["iterations"] = iterations;
  report["solver"]["time_s"] = RoundToDecimals(solve_s, 4);
  report["objective"] = RoundToDecimals(kept_objective, 9);
  report["ladder"] = stages;
  kept.plan.optimized["quality"] = QualityName(options.quality);
  kept.plan.optimized["cost_before"] = first_report["total"]["before"];
  kept.plan.optimized["iterations"] = iterations;
  return kept;
}

Json RetimeJson(const RetimeResult& r) {
  Json j = Json::object();
  Json shots = Json::array();
  for (const RetimedShot& s : r.shots) {
    Json e = Json::object();
    e["shot"] = s.shot;
    e["duration_before_s"] = RoundToDecimals(s.duration_before_s, 6);
    e["duration_after_s"] = RoundToDecimals(s.duration_after_s, 6);
    e["longer_s"] = RoundToDecimals(s.duration_after_s - s.duration_before_s, 6);
    e["slowest_factor"] = RoundToDecimals(s.slowest_factor, 4);
    e["limits"] = s.limits;
    e["broken_samples_before"] = s.broken_samples_before;
    e["broken_samples_after"] = s.broken_samples_after;
    shots.push_back(e);
  }
  j["shots"] = shots;
  j["added_s"] = RoundToDecimals(r.added_s, 6);
  j["notes"] = r.notes;
  return j;
}

}  // namespace

// Rule 7, retiming (optimizer/retime.h): after the ladder, a shot that opted in and still breaks a rate
// limit is flown slower along the path the ladder kept, and the ladder runs again from there (never worse
// than the retimed plan, which is never worse than the ladder's result in any level or other shot).
OptimizeResult OptimizePlan(const OptimizeInput& input, const OptimizeOptions& options) {
  QuietCeresLogging();
  const std::shared_ptr<const SceneIndex> scene = IndexScene(input, options);
  OptimizeResult kept = RunLadder(input, options, scene);
  const bool asks =
      std::any_of(input.plan.shots.begin(), input.plan.shots.end(), [](const ShotSpan& s) { return s.intent.retime; });
  if (!asks) return kept;
  if (!input.others.empty()) {
    RetimeResult none;
    none.notes.push_back("not retimed: the drones of a team share one clock");
    kept.report["retime"] = RetimeJson(none);
    return kept;
  }
  // The shots that opted in and still break a rate limit. Each is retimed on the ladder's result and on
  // the plan as given (whose joins are as planned: an eased shot that ends at rest may change its pace
  // there, which the optimized path, no longer at rest, may not), and the one with fewer samples still
  // broken is optimized again (the ladder's on a tie: it needs less time).
  std::set<std::string> broken;
  for (const auto& v : kept.plan.feasibility.violations) {
    if (TimeOrderOfLimit(v.limit) > 0) broken.insert(v.shot);
  }
  std::unique_ptr<scene::CasterGround> ground;
  if (scene->caster) ground = std::make_unique<scene::CasterGround>(*scene->caster, input.scene_source);
  RetimeResult retimed = RetimeShots(kept.plan, ground.get(), &broken);
  std::string from = "optimized";
  if (retimed.rate_broken_samples > 0) {
    RetimeResult from_input = RetimeShots(input.plan, ground.get(), &broken);
    if (from_input.rate_broken_samples < retimed.rate_broken_samples) retimed = std::move(from_input), from = "planned";
  }
  Json record = RetimeJson(retimed);
  if (!retimed.shots.empty()) record["from"] = from;  // the path retimed: the ladder's result, or the plan's
  if (retimed.shots.empty()) {
    kept.report["retime"] = record;
    return kept;
  }
  record["objective_before_retime"] = kept.report["objective"];
  OptimizeInput again = input;
  again.plan = retimed.plan;
  again.own_live.clear();  // one per sample of the plan before; only a team uses it, and a team is not retimed
  OptimizeResult result = RunLadder(again, options, scene);
  // Never worse than the plan as given, shot by shot, in any limit; else the ladder's first result.
  if (const std::vector<std::string> worse = WorseThan(input.plan, result.plan, ground.get()); !worse.empty()) {
    RetimeResult refused;
    refused.notes.push_back("not retimed: after optimizing, the retimed plan broke " + worse.front() +
                            " by more than the plan as given");
    kept.report["retime"] = RetimeJson(refused);
    return kept;
  }
  result.report["retime"] = record;
  result.plan.optimized["retimed_s"] = record["added_s"];
  return result;
}

Json PlanTermCosts(const OptimizeInput& input, const Trajectory& plan, const OptimizeOptions& options) {
  const std::shared_ptr<const SceneIndex> scene = IndexScene(input, options);
  PlanOptimizer first(input, input.plan, options, scene, nullptr);
  first.Objective();
  PlanOptimizer judge(input, plan, options, scene, &first.samples());
  return judge.BaseTermCosts();
}

}  // namespace cinepath::optimizer
