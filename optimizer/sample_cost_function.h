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

class SampleCostFunction : public ceres::CostFunction {
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
    const SampleState<double> s = EvaluateSample(base_, parameters);
    const double scale = std::sqrt(*stiffness_);
    double* part_jacobians[4];
    for (const Part& p : parts_) {
      if (jacobians) {
        for (int j = 0; j < 4; ++j) part_jacobians[j] = jacobians[j] ? jacobians[j] + p.row * kNumChannels : nullptr;
      }
      if (!p.state->EvaluateAt(s, residuals + p.row, jacobians ? part_jacobians : nullptr)) return false;
      if (!p.stiff || scale == 1.0) continue;
      const int rows = p.cost->num_residuals();
      for (int i = 0; i < rows; ++i) residuals[p.row + i] *= scale;
      if (!jacobians) continue;
      for (int j = 0; j < 4; ++j) {
        if (!part_jacobians[j]) continue;
        for (int i = 0; i < rows * kNumChannels; ++i) part_jacobians[j][i] *= scale;
      }
    }
    return true;
  }

 private:
  struct Part {
    std::unique_ptr<ceres::CostFunction> cost;
    const StatePart* state;  // the same object as `cost`
    int row;                 // its first residual in the block
    bool stiff;
  };
  SampleBase base_;
  const double* stiffness_;
  std::vector<Part> parts_;
};

}  // namespace cinepath::optimizer
