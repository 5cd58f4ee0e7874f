#include "core/feasibility.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "core/angles.h"
#include "core/error.h"
#include "core/optics.h"

namespace cinepath {
namespace {

constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

double DistanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double w = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + w * ab)).norm();
}

}  // namespace

double LimitSeries::Excess(size_t k) const {
  const double v = values[k];
  if (std::isnan(v)) return 0;
  const double slack = 1e-9 * std::max(1.0, std::fabs(limit_value));
  const double over = is_minimum ? limit_value - v : v - limit_value;
  return over > slack ? std::min(over, 1e300) : 0.0;
}

std::vector<FeasibilityViolation> ViolationsOf(const LimitSeries& series, const Trajectory& plan) {
  std::vector<FeasibilityViolation> out;
  bool open = false;
  for (size_t i = 0; i < series.values.size(); ++i) {
    if (series.Excess(i) == 0) {
      open = false;
      continue;
    }
    const double value = std::clamp(series.values[i], -1e300, 1e300);  // an unbounded rate is reported as 1e300
    const auto& s = plan.samples[i];
    if (open && out.back().shot == s.shot) {
      auto& v = out.back();
      v.end_time_s = s.time_s;
      v.worst_value = series.is_minimum ? std::min(v.worst_value, value) : std::max(v.worst_value, value);
    } else {
      FeasibilityViolation v;
      v.limit = series.limit;
      v.shot = s.shot;
      v.start_time_s = v.end_time_s = s.time_s;
      v.worst_value = value;
      v.limit_value = series.limit_value;
      v.unit = series.unit;
      out.push_back(v);
      open = true;
    }
  }
  return out;
}

std::vector<LimitSeries> MeasureLimits(const Trajectory& plan, const std::vector<bool>& cut_before,
                                       const std::vector<LensRequest>& requests, const Ground* ground) {
  const auto& S = plan.samples;
  const size_t n = S.size();
  CINEPATH_CHECK(cut_before.size() == n);
  CINEPATH_CHECK(requests.empty() || requests.size() == n);
  const DroneProfile& d = plan.drone;
  const CameraSpec& c = plan.camera;
  const double dt = 1.0 / plan.frame_rate_hz;

  // Segment id per sample: a cut starts a new segment.
  std::vector<size_t> seg(n, 0);
  for (size_t i = 1; i < n; ++i) seg[i] = seg[i - 1] + (cut_before[i] ? 1 : 0);
  auto same = [&](long a, long b) {
    return a >= 0 && b >= 0 && static_cast<size_t>(a) < n && static_cast<size_t>(b) < n && seg[a] == seg[b];
  };
  auto p = [&](long i) -> const Eigen::Vector3d& { return S[i].position_enu_m; };

  std::vector<LimitSeries> tracks;
  enum {
    kSpeed,
    kClimb,
    kDescent,
    kAccel,
    kJerk,
    kYawRate,
    kPitchMin,
    kPitchMax,
    kPitchRate,
    kAltMin,
    kAltMax,
    kSubject,
    kFocalMin,
    kFocalMax,
    kFocusMin,
    kFNumberMin,
    kFNumberMax,
    kFocalRate,
    kFocusRate,
    kApertureRate,
    kTerrain
  };
  tracks.push_back(
      {"horizontal_speed", "m/s", d.max_horizontal_speed_m_s, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"climb_rate", "m/s", d.max_climb_rate_m_s, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"descent_rate", "m/s", d.max_descent_rate_m_s, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back(
      {"horizontal_acceleration", "m/s^2", d.max_acceleration_m_s2, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"jerk", "m/s^3", d.max_jerk_m_s3, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"yaw_rate", "deg/s", d.max_yaw_rate_deg_s, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"gimbal_pitch_min", "deg", d.min_gimbal_pitch_deg, true, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"gimbal_pitch_max", "deg", d.max_gimbal_pitch_deg, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back(
      {"gimbal_pitch_rate", "deg/s", d.max_gimbal_pitch_rate_deg_s, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"altitude_min", "m", d.min_altitude_m, true, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"altitude_max", "m", d.max_altitude_m, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"subject_distance", "m", d.min_subject_distance_m, true, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"focal_length_min", "mm", c.min_focal_length_mm, true, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"focal_length_max", "mm", c.max_focal_length_mm, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"focus_distance_min", "m", c.min_focus_distance_m, true, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"f_number_min", "", c.min_f_number, true, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"f_number_max", "", c.max_f_number, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"focal_length_rate", "mm/s", c.max_focal_rate_mm_s, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"focus_rate", "m/s", c.max_focus_rate_m_s, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back(
      {"aperture_rate", "stops/s", c.max_aperture_rate_stops_s, false, std::vector<double>(n, kNotMeasured)});
  tracks.push_back({"terrain_clearance", "m", d.min_terrain_clearance_m, true, std::vector<double>(n, kNotMeasured)});

  // Altitude limits hold above the take-off point, as the autopilots apply them: ENU z = 0, or with
  // the mesh, the ground under the first sample (the drone takes off below where the plan starts).
  double takeoff_up_m = 0;
  if (ground && n > 0) {
    const Eigen::Vector3d& start = plan.samples[0].position_enu_m;
    takeoff_up_m = ground->SurfaceUpM(start.x(), start.y()).value_or(0.0);
  }
  for (size_t k = 0; k < n; ++k) {
    const long i = static_cast<long>(k);
    const auto& s = S[k];
    // Velocity.
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    bool have_v = true;  // a sample alone in its segment has no velocity (nor any other rate)
    if (same(i - 1, i + 1)) {
      v = (p(i + 1) - p(i - 1)) / (2 * dt);
    } else if (same(i, i + 1)) {
      v = (p(i + 1) - p(i)) / dt;
    } else if (same(i - 1, i)) {
      v = (p(i) - p(i - 1)) / dt;
    } else {
      have_v = false;
    }
    if (have_v) {
      tracks[kSpeed].values[k] = std::hypot(v.x(), v.y());
      tracks[kClimb].values[k] = v.z();
      tracks[kDescent].values[k] = -v.z();
    }
    if (same(i - 1, i + 1)) {
      const Eigen::Vector3d a = (p(i + 1) - 2 * p(i) + p(i - 1)) / (dt * dt);
      tracks[kAccel].values[k] = std::hypot(a.x(), a.y());
    }
    if (same(i - 1, i + 2)) {
      const Eigen::Vector3d j = (p(i + 2) - 3 * p(i + 1) + 3 * p(i) - p(i - 1)) / (dt * dt * dt);
      tracks[kJerk].values[k] = j.norm();
    }
    const bool back = same(i - 1, i);
    if (back) {
      const auto& q = S[k - 1];
      tracks[kYawRate].values[k] = std::fabs(AngleDiffDeg(q.drone_heading_deg, s.drone_heading_deg)) / dt;
      tracks[kPitchRate].values[k] = std::fabs(s.gimbal_pitch_deg - q.gimbal_pitch_deg) / dt;
      tracks[kFocalRate].values[k] = std::fabs(s.focal_length_mm - q.focal_length_mm) / dt;
      // Focus moves beyond the hyperfocal distance change nothing visible: clamp both ends to it.
      const double coc = c.coc_mm > 0 ? c.coc_mm : DefaultCocMm(c.sensor_width_mm, c.sensor_height_mm);
      const double h = HyperfocalDistanceM(s.focal_length_mm, s.f_number, coc);
      const double f0 = std::min(q.focus_distance_m, h), f1 = std::min(s.focus_distance_m, h);
      tracks[kFocusRate].values[k] = std::fabs(f1 - f0) / dt;
      tracks[kApertureRate].values[k] = std::fabs(StopsBetween(q.f_number, s.f_number)) / dt;
    }
    tracks[kPitchMin].values[k] = s.gimbal_pitch_deg;
    tracks[kPitchMax].values[k] = s.gimbal_pitch_deg;
    tracks[kAltMin].values[k] = s.position_enu_m.z() - takeoff_up_m;
    tracks[kAltMax].values[k] = s.position_enu_m.z() - takeoff_up_m;
    if (!plan.subjects.empty()) {
      double nearest = std::numeric_limits<double>::infinity();
      for (const auto& subj : plan.subjects) {
        const Eigen::Vector3d& base = subj.positions_enu_m[k];
        nearest =
            std::min(nearest, DistanceToSegment(s.position_enu_m, base, base + Eigen::Vector3d(0, 0, subj.height_m)));
      }
      tracks[kSubject].values[k] = nearest;
    }
    const LensRequest r =
        requests.empty() ? LensRequest{s.focal_length_mm, s.focus_distance_m, s.f_number} : requests[k];
    tracks[kFocalMin].values[k] = r.focal_length_mm;
    tracks[kFocalMax].values[k] = r.focal_length_mm;
    tracks[kFocusMin].values[k] = r.focus_distance_m;
    tracks[kFNumberMin].values[k] = r.f_number;
    tracks[kFNumberMax].values[k] = r.f_number;
    if (ground) {
      // Above the highest surface under the camera; off the mesh there is nothing to clear.
      const std::optional<double> ground_up = ground->SurfaceUpM(s.position_enu_m.x(), s.position_enu_m.y());
      if (ground_up) tracks[kTerrain].values[k] = s.position_enu_m.z() - *ground_up;
    }
  }
  return tracks;
}

FeasibilityReport CheckFeasibility(const Trajectory& plan, const std::vector<bool>& cut_before,
                                   const std::vector<LensRequest>& requests, const Ground* ground) {
  FeasibilityReport report;
  if (!ground) report.skipped.push_back("terrain_clearance: no scene mesh to check against");
  for (const auto& t : MeasureLimits(plan, cut_before, requests, ground)) {
    const auto v = ViolationsOf(t, plan);
    report.violations.insert(report.violations.end(), v.begin(), v.end());
  }
  std::stable_sort(
      report.violations.begin(), report.violations.end(),
      [](const FeasibilityViolation& a, const FeasibilityViolation& b) { return a.start_time_s < b.start_time_s; });
  return report;
}

}  // namespace cinepath
