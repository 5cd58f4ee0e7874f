// A cost functor linear in its four knots (SmoothnessCost) as a Ceres cost function whose Jacobian is a
// constant (docs/optimize.md, "Speed"): taken once by automatic differentiation when the cost function is made,
// then copied at every evaluation, the residuals computed by the functor in doubles. Automatic differentiation of
// a linear functor does not read the point (each derivative is the functor's coefficients combined by the same
// operations wherever it is evaluated), so the Jacobian and the residuals are the same numbers as
// ceres::AutoDiffCostFunction gives at every point, without its Jets at every evaluation.
#pragma once

#include <algorithm>
#include <array>
#include <memory>

#include <ceres/autodiff_cost_function.h>
#include <ceres/sized_cost_function.h>

#include "optimizer/sample_model.h"

namespace cinepath::optimizer {

// A cost function whose Jacobian is the same at every point: the banded solver (optimizer/banded_solver.h) takes
// its Gauss-Newton matrix J^T J once and evaluates only its residuals after.
class ConstantJacobian {
 public:
  virtual ~ConstantJacobian() = default;
  // The Jacobian in parameter block j, row-major (residuals x the block's size), as Evaluate writes it.
  virtual const double* constant_jacobian(int j) const = 0;
};

template <typename Functor, int kResiduals>
class LinearCostFunction
    : public ceres::SizedCostFunction<kResiduals, kNumChannels, kNumChannels, kNumChannels, kNumChannels>,
      public ConstantJacobian {
 public:
  explicit LinearCostFunction(Functor* functor) : functor_(functor) {
    const ceres::AutoDiffCostFunction<Functor, kResiduals, kNumChannels, kNumChannels, kNumChannels, kNumChannels>
        automatic(new Functor(*functor));
    const double zero[kNumChannels] = {};
    const double* at[4] = {zero, zero, zero, zero};
    double residuals[kResiduals];
    double* jacobians[4];
    for (int j = 0; j < 4; ++j) jacobians[j] = jacobian_[j].data();
    automatic.Evaluate(at, residuals, jacobians);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    if (!(*functor_)(parameters[0], parameters[1], parameters[2], parameters[3], residuals)) return false;
    if (!jacobians) return true;
    for (int j = 0; j < 4; ++j) {
      if (jacobians[j]) std::copy(jacobian_[j].begin(), jacobian_[j].end(), jacobians[j]);
    }
    return true;
  }
  const double* constant_jacobian(int j) const override { return jacobian_[j].data(); }

 private:
  std::unique_ptr<Functor> functor_;
  std::array<std::array<double, kResiduals * kNumChannels>, 4> jacobian_{};  // per knot, row-major
};

}  // namespace cinepath::optimizer
