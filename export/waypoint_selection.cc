#include "export/waypoint_selection.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/error.h"

namespace cinepath::exporter {

void SelectionOptions::Check() const {
  if (!std::isfinite(max_deviation_m) || max_deviation_m <= 0) {
    throw InputError("max_deviation_m: must be a finite number > 0");
  }
  if (!std::isfinite(max_angle_deg) || max_angle_deg <= 0) {
    throw InputError("max_angle_deg: must be a finite number > 0");
  }
}

namespace {

// Linear interpolation of an angle along the shortest way round.
double LerpAngleDeg(double a_deg, double b_deg, double t) { return a_deg + t * AngleDiffDeg(a_deg, b_deg); }

}  // namespace

LegError MeasureLeg(const std::vector<TrajectorySample>& samples, int a, int b) {
  return MeasureLeg(samples, a, b, nullptr, RoiTracking::kNone);
}

LegError MeasureLeg(const std::vector<TrajectorySample>& samples, int a, int b, const RoiStretch* roi,
                    RoiTracking tracking) {
  if (!roi) tracking = RoiTracking::kNone;
  LegError error;
  const TrajectorySample& sa = samples[a];
  const TrajectorySample& sb = samples[b];
  const Eigen::Vector3d leg = sb.position_enu_m - sa.position_enu_m;
  const double leg_length_sq = leg.squaredNorm();
  const double duration_s = sb.time_s - sa.time_s;
  for (int k = a + 1; k < b; ++k) {
    const TrajectorySample& s = samples[k];
    // Projection parameter along the leg; on a zero-length leg (hovering) time decides.
    double t;
    if (leg_length_sq > 1e-12) {
      t = std::clamp((s.position_enu_m - sa.position_enu_m).dot(leg) / leg_length_sq, 0.0, 1.0);
    } else {
      t = duration_s > 0 ? std::clamp((s.time_s - sa.time_s) / duration_s, 0.0, 1.0) : 0.0;
    }
    const Eigen::Vector3d flown = sa.position_enu_m + t * leg;
    error.deviation_m = std::max(error.deviation_m, (s.position_enu_m - flown).norm());
    if (tracking == RoiTracking::kCamera) {
      // The camera looks at the ROI from where the drone actually is.
      const Eigen::Vector3d to_roi = roi->point_enu_m - flown;
      const double cos_angle = to_roi.norm() > 1e-9 ? OpticalAxisEnu(s).dot(to_roi.normalized()) : -1.0;
      error.angle_deg = std::max(error.angle_deg, DegFromRad(std::acos(std::clamp(cos_angle, -1.0, 1.0))));
      continue;
    }
    double heading = LerpAngleDeg(sa.drone_heading_deg, sb.drone_heading_deg, t);
    if (tracking == RoiTracking::kHeading) {
      // The nose points at the ROI horizontally (compass bearing from the flown point).
      const Eigen::Vector3d to_roi = roi->point_enu_m - flown;
      heading = to_roi.head<2>().norm() > 1e-9 ? HeadingDegFromEnuYaw(std::atan2(to_roi.y(), to_roi.x())) : heading;
    }
    const double pitch = sa.gimbal_pitch_deg + t * (sb.gimbal_pitch_deg - sa.gimbal_pitch_deg);
    const double gyaw = LerpAngleDeg(sa.gimbal_yaw_deg, sb.gimbal_yaw_deg, t);
    error.angle_deg = std::max({error.angle_deg, std::abs(AngleDiffDeg(heading, s.drone_heading_deg)),
                                std::abs(pitch - s.gimbal_pitch_deg), std::abs(AngleDiffDeg(gyaw, s.gimbal_yaw_deg))});
  }
  return error;
}

Selection SelectWaypoints(const std::vector<TrajectorySample>& samples, const SelectionOptions& options) {
  options.Check();
  CINEPATH_CHECK(!samples.empty());
  Selection selection;
  const int n = static_cast<int>(samples.size());
  // Samples that must be waypoints: the ends of every point-of-interest stretch.
  std::vector<int> forced;
  for (const RoiStretch& r : options.rois) {
    CINEPATH_CHECK(r.first_sample >= 0 && r.first_sample < r.last_sample && r.last_sample < n);
    forced.push_back(r.first_sample);
    forced.push_back(r.last_sample);
  }
  std::sort(forced.begin(), forced.end());
  // The stretch a leg starting at sample a lies in (legs never straddle a stretch's ends).
  auto stretch_of = [&](int a) -> const RoiStretch* {
    for (const RoiStretch& r : options.rois) {
      if (a >= r.first_sample && a < r.last_sample) return &r;
    }
    return nullptr;
  };
  int a = 0;
  selection.sample_indices.push_back(0);
  while (a < n - 1) {
    const auto next_forced = std::upper_bound(forced.begin(), forced.end(), a);
    const int limit = next_forced == forced.end() ? n - 1 : *next_forced;
    const RoiStretch* roi = stretch_of(a);
    int b = a + 1;
    LegError accepted{};  // a→a+1 has no interior samples
    while (b + 1 <= limit) {
      const LegError trial = MeasureLeg(samples, a, b + 1, roi, options.roi_tracking);
      if (trial.deviation_m > options.max_deviation_m || trial.angle_deg > options.max_angle_deg) break;
      accepted = trial;
      ++b;
    }
    selection.max_deviation_m = std::max(selection.max_deviation_m, accepted.deviation_m);
    selection.max_angle_error_deg = std::max(selection.max_angle_error_deg, accepted.angle_deg);
    selection.sample_indices.push_back(b);
    a = b;
  }
  return selection;
}

}  // namespace cinepath::exporter
