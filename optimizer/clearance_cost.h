// clearance: the camera at least `margin_m` from the nearest surface of the scene's mesh. The residual is
// weight * max(0, margin - d + shift) / margin with d the distance to the closest surface point q
// (scene/surface_distance.h), negative behind the closest face (inside a solid, under terrain); its gradient in the
// camera position is exact, -(c - q) / (d margin), and the knots get it through the sample's spline weights. Analytic,
// since the distance comes from a tree query that automatic differentiation cannot see through.
#pragma once

#include <ceres/sized_cost_function.h>

#include "optimizer/sample_model.h"
#include "optimizer/state_cost_function.h"
#include "scene/surface_distance.h"

namespace cinepath::optimizer {

class ClearanceCost : public ceres::SizedCostFunction<1, kNumChannels, kNumChannels, kNumChannels, kNumChannels>,
                      public StatePart {
 public:
  ClearanceCost(const SampleBase& base, const scene::SurfaceDistance* surface, double margin_m, double weight)
      : base_(base), surface_(surface), margin_m_(margin_m), weight_(weight) {}
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    return EvaluateAt(EvaluateSample(base_, parameters), residuals, jacobians, base_.knots);
  }
  bool EvaluateState(const SampleState<double>& s, double* residuals, double* state_rows) const override;
  int rows() const override { return 1; }
  // The augmented Lagrangian's multiplier update (docs/optimize.md, "Limits as constraints"), the
  // residual being weight max(0, margin - d + shift) / margin: shift = max(0, shift + margin - d). Returns
  // (margin - d) / margin.
  double UpdateShifts(const double* const* parameters);
  double ResetShift() { return shift_m_ = 0; }
  double shift_m() const { return shift_m_; }
  // Bench only (the constrained peer, OptimizeOptions::constrained_solver): the residual becomes the signed
  // margin (margin - d) / margin, without hinge, weight or shift: the clearance holds where it is <= 0.
  void SetSignedMargin() { signed_margin_ = true; }

 private:
  // The distance counted: negative behind the closest face (inside a solid, under terrain).
  double SignedDistanceM(const Eigen::Vector3d& position) const;
  // The direction out of the surface at `position`: along the offset from its closest point, or along the
  // face normal when on or behind it.
  static Eigen::Vector3d Away(const scene::SurfacePoint& closest, const Eigen::Vector3d& position);
  double shift_m_ = 0;
  bool signed_margin_ = false;
  SampleBase base_;
  const scene::SurfaceDistance* surface_;
  double margin_m_;
  double weight_;
};

}  // namespace cinepath::optimizer
