#include "optimizer/clearance_cost.h"

namespace cinepath::optimizer {

bool ClearanceCost::EvaluateState(const SampleState<double>& s, double* residuals, double* state_rows) const {
  const auto closest = surface_->Closest(s.position);
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // d residual / d camera position
  residuals[0] = 0;
  // Behind the closest face (inside a solid, under terrain) the distance counts as negative: the residual
  // keeps growing and the push points out through that face.
  const double signed_m = closest ? (closest->behind ? -closest->distance_m : closest->distance_m) : margin_m_;
  if (signed_margin_) {
    residuals[0] = (margin_m_ - signed_m) / margin_m_;
    if (closest) gradient = -Away(*closest, s.position) / margin_m_;
  } else if (closest && signed_m < margin_m_ + shift_m_) {
    residuals[0] = weight_ * (margin_m_ + shift_m_ - signed_m) / margin_m_;
    gradient = -weight_ / margin_m_ * Away(*closest, s.position);
  }
  if (state_rows) {  // the camera position is the state's first three fields
    std::fill(state_rows, state_rows + kStateFields, 0.0);
    for (int c = 0; c < 3; ++c) state_rows[c] = gradient[c];
  }
  return true;
}

Eigen::Vector3d ClearanceCost::Away(const scene::SurfacePoint& closest, const Eigen::Vector3d& position) {
  const Eigen::Vector3d offset = position - closest.position_enu_m;
  return closest.distance_m > 1e-9 ? Eigen::Vector3d(offset / closest.distance_m * (closest.behind ? -1.0 : 1.0))
                                   : closest.normal_enu;
}

double ClearanceCost::SignedDistanceM(const Eigen::Vector3d& position) const {
  const auto closest = surface_->Closest(position);
  if (!closest) return margin_m_;
  return closest->behind ? -closest->distance_m : closest->distance_m;
}

double ClearanceCost::UpdateShifts(const double* const* parameters) {
  const double short_m = margin_m_ - SignedDistanceM(EvaluateSample(base_, parameters).position);
  shift_m_ = std::max(0.0, shift_m_ + short_m);
  return short_m / margin_m_;
}

}  // namespace cinepath::optimizer
