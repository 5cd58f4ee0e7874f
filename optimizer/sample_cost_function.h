// A sample's one-sample terms (framing, depth of field, background blur, limits, keep-out, the team's terms,
// clearance) stacked in one residual block (docs/optimize.md, "Speed"): the sample's state is evaluated once
// for all of them, and the solve has one block of (say) 9 rows per sample instead of four of 1 to 4 rows, so
// every Jacobian product and the Gauss-Newton matrix handle a quarter of the small dense cells.
//
// Each part keeps its own cost function (optimizer/state_cost_function.h, optimizer/clearance_cost.h), so the
// optimizer still reports, weights and constrains each term on its own; the parts' residuals are the same
// numbers as in blocks of their own. A stiff part (the limits, keep-out, the team's separation and
// out-of-shot) is scaled by the continuation's stiffness, which a block of its own took as a ScaledLoss: the
// cost s |r|^2 / 2 is the residual and Jacobian times sqrt(s), which is what Ceres does with that loss.
#pragma once

#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include <ceres/cost_function.h>

#include "optimizer/sample_model.h"
#include "optimizer/state_cost_function.h"

namespace cinepath::optimizer {

class SampleCostFunction : public ceres::CostFunction, public StateBlock {
 public:
  // `stiffness`: the continuation's scale on the stiff parts' cost, read at every evaluation (1: full weight).
  SampleCostFunction(const SampleBase& base, const double* stiffness) : base_(base), stiffness_(stiffness) {
    for (int j = 0; j < 4; ++j) mutable_parameter_block_sizes()->push_back(kNumChannels);
  }

  // Stacks `part` (a cost function on the sample's four knots that is also a StatePart) below the others.
  // Only before the block joins a problem.
  // `goal`: a smooth goal of the objective (framing, background blur), which a solve on the coarse grid of goals
  // weights or leaves out (GoalWeightedSample); the rest (the limits, and the depth of field's hinge) stay at
  // every sample.
  template <typename Part>
  void Add(std::unique_ptr<Part> part, bool stiff, bool goal) {
    const int rows = part->num_residuals();
    const StatePart* state = part.get();
    parts_.push_back({std::move(part), state, num_residuals(), stiff, goal});
    set_num_residuals(num_residuals() + rows);
    has_limits_ = has_limits_ || !goal;
  }
  bool empty() const { return parts_.empty(); }
  bool has_limits() const { return has_limits_; }  // a part that is not a goal

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    if (!jacobians) return EvaluateRows(parameters, residuals, nullptr, true);
    std::vector<double>& state_rows = StateRowsBuffer(num_residuals());
    if (!EvaluateRows(parameters, residuals, state_rows.data(), false)) return false;
    StateRowsToKnots(base_.knots, state_rows.data(), num_residuals(), jacobians);
    const double scale = std::sqrt(*stiffness_);  // the stiff parts' Jacobian rows, as Ceres scales a loss's
    if (scale == 1.0) return true;
    for (const Part& p : parts_) {
      if (!p.stiff) continue;
      for (int j = 0; j < 4; ++j) {
        if (!jacobians[j]) continue;
        double* rows = jacobians[j] + p.row * kNumChannels;
        for (int i = 0; i < p.state->rows() * kNumChannels; ++i) rows[i] *= scale;
      }
    }
    return true;
  }

  // The rows in the sample's state (StateBlock): each part's, a stiff part's times sqrt(stiffness).
  bool EvaluateStateBlock(double const* const* parameters, double* residuals, double* state_rows) const override {
    return EvaluateRows(parameters, residuals, state_rows, true);
  }
  // The goals' rows times sqrt(goal_weight); at 0 they are not evaluated (zero rows).
  bool EvaluateRows(double const* const* parameters, double* residuals, double* state_rows, bool scale_rows,
                    double goal_weight = 1.0) const {
    const SampleState<double> s = EvaluateSample(base_, parameters);
    const double stiff_scale = std::sqrt(*stiffness_), goal_scale = std::sqrt(goal_weight);
    for (const Part& p : parts_) {
      double* rows = state_rows ? state_rows + p.row * kStateFields : nullptr;
      const int n = p.state->rows();
      if (p.goal && goal_weight == 0) {
        std::fill(residuals + p.row, residuals + p.row + n, 0.0);
        if (rows) std::fill(rows, rows + n * kStateFields, 0.0);
        continue;
      }
      if (!p.state->EvaluateState(s, residuals + p.row, rows)) return false;
      const double scale = p.stiff ? stiff_scale : p.goal ? goal_scale : 1.0;
      if (scale == 1.0) continue;
      for (int i = 0; i < n; ++i) residuals[p.row + i] *= scale;
      if (rows && scale_rows) {
        for (int i = 0; i < n * kStateFields; ++i) rows[i] *= scale;
      }
    }
    return true;
  }
  const KnotWeights& knot_weights() const override { return base_.knots; }

 private:
  struct Part {
    std::unique_ptr<ceres::CostFunction> cost;
    const StatePart* state;  // the same object as `cost`
    int row;                 // its first residual in the block
    bool stiff, goal;
  };
  bool has_limits_ = false;
  // A buffer per thread for Evaluate's state rows (a block has no fixed row count).
  static std::vector<double>& StateRowsBuffer(int rows) {
    thread_local std::vector<double> buffer;
    buffer.resize(static_cast<size_t>(rows) * kStateFields);
    return buffer;
  }
  SampleBase base_;
  const double* stiffness_;
  std::vector<Part> parts_;
};

// A sample block on the coarse grid of goals (docs/optimize.md, "Speed"): its goals weighted by `goal_weight`
// (the grid's stride, so that the goals' sums still approximate the same integrals over time; 0 off the
// grid, where they are not evaluated), its limits as they are. Does not own the block.
class GoalWeightedSample : public ceres::CostFunction, public StateBlock {
 public:
  GoalWeightedSample(const SampleCostFunction* block, double goal_weight) : block_(block), goal_weight_(goal_weight) {
    set_num_residuals(block->num_residuals());
    *mutable_parameter_block_sizes() = block->parameter_block_sizes();
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    if (!jacobians) return block_->EvaluateRows(parameters, residuals, nullptr, true, goal_weight_);
    std::vector<double> state_rows(static_cast<size_t>(num_residuals()) * kStateFields);
    if (!block_->EvaluateRows(parameters, residuals, state_rows.data(), true, goal_weight_)) return false;
    StateRowsToKnots(block_->knot_weights(), state_rows.data(), num_residuals(), jacobians);
    return true;
  }
  bool EvaluateStateBlock(double const* const* parameters, double* residuals, double* state_rows) const override {
    return block_->EvaluateRows(parameters, residuals, state_rows, true, goal_weight_);
  }
  const KnotWeights& knot_weights() const override { return block_->knot_weights(); }

 private:
  const SampleCostFunction* block_;
  double goal_weight_;
};

}  // namespace cinepath::optimizer
