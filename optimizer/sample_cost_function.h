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
  template <typename Part>
  void Add(std::unique_ptr<Part> part, bool stiff) {
    const int rows = part->num_residuals();
    const StatePart* state = part.get();
    parts_.push_back({std::move(part), state, num_residuals(), stiff});
    set_num_residuals(num_residuals() + rows);
  }
  bool empty() const { return parts_.empty(); }

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
  const KnotWeights& knot_weights() const override { return base_.knots; }

 private:
  // The parts' residuals (a stiff part's times sqrt(stiffness)) and state rows (scaled too when `scale_rows`).
  bool EvaluateRows(double const* const* parameters, double* residuals, double* state_rows, bool scale_rows) const {
    const SampleState<double> s = EvaluateSample(base_, parameters);
    const double scale = std::sqrt(*stiffness_);
    for (const Part& p : parts_) {
      double* rows = state_rows ? state_rows + p.row * kStateFields : nullptr;
      if (!p.state->EvaluateState(s, residuals + p.row, rows)) return false;
      if (!p.stiff || scale == 1.0) continue;
      const int n = p.state->rows();
      for (int i = 0; i < n; ++i) residuals[p.row + i] *= scale;
      if (rows && scale_rows) {
        for (int i = 0; i < n * kStateFields; ++i) rows[i] *= scale;
      }
    }
    return true;
  }
  struct Part {
    std::unique_ptr<ceres::CostFunction> cost;
    const StatePart* state;  // the same object as `cost`
    int row;                 // its first residual in the block
    bool stiff;
  };
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

}  // namespace cinepath::optimizer
