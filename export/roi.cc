#include "export/roi.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/angles.h"

namespace cinepath::exporter {

Eigen::Vector3d OpticalAxisEnu(const TrajectorySample& sample) {
  return (sample.world_from_camera.normalized() * Eigen::Vector3d::UnitZ()).normalized();
}

namespace {

// Angle (deg) between a unit axis and the direction from `from` to `to`; 180 when they coincide.
double AxisAngleDeg(const Eigen::Vector3d& axis, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d v = to - from;
  const double length = v.norm();
  if (!(length > 1e-9)) return 180.0;
  return DegFromRad(std::acos(std::clamp(axis.dot(v) / length, -1.0, 1.0)));
}

}  // namespace

RoiFit FitRoi(const std::vector<TrajectorySample>& samples, int first, int last, double max_angle_deg,
              bool require_spread) {
  RoiFit fit;
  if (last <= first) return fit;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  Eigen::Vector3d mean_axis = Eigen::Vector3d::Zero();
  for (int i = first; i <= last; ++i) {
    const Eigen::Vector3d d = OpticalAxisEnu(samples[i]);
    const Eigen::Matrix3d reject = Eigen::Matrix3d::Identity() - d * d.transpose();
    a += reject;
    b += reject * samples[i].position_enu_m;
    mean_axis += d;
  }
  // Spread of the axes: if they all lie within 2 × tolerance of their mean direction, the point is
  // not observable along the axis.
  if (!(mean_axis.norm() > 1e-12)) return fit;
  mean_axis.normalize();
  double spread_deg = 0;
  for (int i = first; i <= last; ++i) {
    spread_deg =
        std::max(spread_deg, DegFromRad(std::acos(std::clamp(OpticalAxisEnu(samples[i]).dot(mean_axis), -1.0, 1.0))));
  }
  if (require_spread && spread_deg <= 2 * max_angle_deg) return fit;
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(a);
  if (ldlt.info() != Eigen::Success) return fit;
  fit.point_enu_m = ldlt.solve(b);
  if (!fit.point_enu_m.allFinite()) return fit;
  for (int i = first; i <= last; ++i) {
    fit.max_angle_deg = std::max(fit.max_angle_deg,
                                 AxisAngleDeg(OpticalAxisEnu(samples[i]), samples[i].position_enu_m, fit.point_enu_m));
    if (fit.max_angle_deg > max_angle_deg) return fit;
  }
  fit.accepted = true;
  return fit;
}

std::vector<RoiStretch> DetectRoiStretches(const std::vector<TrajectorySample>& samples, const RoiOptions& options) {
  std::vector<RoiStretch> stretches;
  const int n = static_cast<int>(samples.size());
  // Smallest stretch: the first sample at least min_duration_s after `first`.
  auto min_last = [&](int first) {
    int last = first + 1;
    while (last < n && samples[last].time_s - samples[first].time_s < options.min_duration_s) ++last;
    return last;
  };
  int first = 0;
  while (first < n - 1) {
    const int shortest = min_last(first);
    if (shortest >= n || !FitRoi(samples, first, shortest, options.max_angle_deg, false).accepted) {
      ++first;
      continue;
    }
    // Gallop then bisect for the longest accepted stretch (acceptance is checked exactly at the end).
    int good = shortest;
    int step = 1;
    int bad = n;
    while (good + step < n) {
      if (FitRoi(samples, first, good + step, options.max_angle_deg, false).accepted) {
        good += step;
        step *= 2;
      } else {
        bad = good + step;
        break;
      }
    }
    if (bad == n && good < n - 1 && FitRoi(samples, first, n - 1, options.max_angle_deg, false).accepted) good = n - 1;
    while (bad - good > 1 && good < n - 1) {
      const int mid = good + (bad - good) / 2;
      if (FitRoi(samples, first, mid, options.max_angle_deg, false).accepted) {
        good = mid;
      } else {
        bad = mid;
      }
    }
    // The start was found with a window of min_duration_s, which may reject the slow beginning of a
    // long stretch (a distant flyby pans slowly): extend it backwards as far as it stays accepted.
    const int earliest = stretches.empty() ? 0 : stretches.back().last_sample + 1;
    int start = first;
    int lo = earliest - 1;  // known bad (or before the range)
    while (start - lo > 1) {
      const int mid = lo + (start - lo) / 2;
      if (FitRoi(samples, mid, good, options.max_angle_deg, false).accepted) {
        start = mid;
      } else {
        lo = mid;
      }
    }
    const RoiFit fit = FitRoi(samples, start, good, options.max_angle_deg);
    // Coherent axes without an observable point (near-parallel: a dolly, a locked-off shot): no ROI.
    if (fit.accepted) stretches.push_back({start, good, fit.point_enu_m, fit.max_angle_deg});
    first = good + 1;
  }
  return stretches;
}

}  // namespace cinepath::exporter
