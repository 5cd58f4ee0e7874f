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

namespace {

// One series per limit, in this order.
enum LimitTrack {
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

std::vector<LimitSeries> UnmeasuredTracks(const DroneProfile& d, const CameraSpec& c, size_t n) {
  const std::vector<double> none(n, kNotMeasured);
  return {
      {"horizontal_speed", "m/s", d.max_horizontal_speed_m_s, false, none},
      {"climb_rate", "m/s", d.max_climb_rate_m_s, false, none},
      {"descent_rate", "m/s", d.max_descent_rate_m_s, false, none},
      {"horizontal_acceleration", "m/s^2", d.max_acceleration_m_s2, false, none},
      {"jerk", "m/s^3", d.max_jerk_m_s3, false, none},
      {"yaw_rate", "deg/s", d.max_yaw_rate_deg_s, false, none},
      {"gimbal_pitch_min", "deg", d.min_gimbal_pitch_deg, true, none},
      {"gimbal_pitch_max", "deg", d.max_gimbal_pitch_deg, false, none},
      {"gimbal_pitch_rate", "deg/s", d.max_gimbal_pitch_rate_deg_s, false, none},
      {"altitude_min", "m", d.min_altitude_m, true, none},
      {"altitude_max", "m", d.max_altitude_m, false, none},
      {"subject_distance", "m", d.min_subject_distance_m, true, none},
      {"focal_length_min", "mm", c.min_focal_length_mm, true, none},
      {"focal_length_max", "mm", c.max_focal_length_mm, false, none},
      {"focus_distance_min", "m", c.min_focus_distance_m, true, none},
      {"f_number_min", "", c.min_f_number, true, none},
      {"f_number_max", "", c.max_f_number, false, none},
      {"focal_length_rate", "mm/s", c.max_focal_rate_mm_s, false, none},
      {"focus_rate", "m/s", c.max_focus_rate_m_s, false, none},
      {"aperture_rate", "stops/s", c.max_aperture_rate_stops_s, false, none},
      {"terrain_clearance", "m", d.min_terrain_clearance_m, true, none},
  };
}

}  // namespace

bool IsMinimumLimit(const std::string& limit) {
  for (const LimitSeries& series : UnmeasuredTracks(DroneProfile{}, CameraSpec{}, 0)) {
    if (series.limit == limit) return series.is_minimum;
  }
  return false;
}

namespace {

// The samples as segments between cuts: finite differences never reach across a cut.
struct Segments {
  const std::vector<TrajectorySample>& samples;
  std::vector<size_t> id;  // per sample; a cut starts a new segment

  Segments(const std::vector<TrajectorySample>& s, const std::vector<bool>& cut_before) : samples(s), id(s.size(), 0) {
    for (size_t i = 1; i < id.size(); ++i) id[i] = id[i - 1] + (cut_before[i] ? 1 : 0);
  }
  // Both samples exist and lie in one segment.
  bool Same(long a, long b) const {
    const size_t n = id.size();
    return a >= 0 && b >= 0 && static_cast<size_t>(a) < n && static_cast<size_t>(b) < n && id[a] == id[b];
  }
  const Eigen::Vector3d& P(long i) const { return samples[i].position_enu_m; }
};

// Altitude limits hold above the take-off point, as the autopilots apply them: ENU z = 0, or with
// the mesh, the ground under the first sample (the drone takes off below where the plan starts).
double TakeoffUpM(const Trajectory& plan, const Ground* ground) {
  if (!ground || plan.samples.empty()) return 0;
  const Eigen::Vector3d& start = plan.samples[0].position_enu_m;
  return ground->SurfaceUpM(start.x(), start.y()).value_or(0.0);
}

// Speed, climb and descent, acceleration and jerk at sample k, by finite differences within its segment.
void MeasureMotion(const Segments& g, size_t k, double dt, std::vector<LimitSeries>& tracks) {
  const long i = static_cast<long>(k);
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  bool have_v = true;  // a sample alone in its segment has no velocity (nor any other rate)
  if (g.Same(i - 1, i + 1)) {
    v = (g.P(i + 1) - g.P(i - 1)) / (2 * dt);
  } else if (g.Same(i, i + 1)) {
    v = (g.P(i + 1) - g.P(i)) / dt;
  } else if (g.Same(i - 1, i)) {
    v = (g.P(i) - g.P(i - 1)) / dt;
  } else {
    have_v = false;
  }
  if (have_v) {
    tracks[kSpeed].values[k] = std::hypot(v.x(), v.y());
    tracks[kClimb].values[k] = v.z();
    tracks[kDescent].values[k] = -v.z();
  }
  if (g.Same(i - 1, i + 1)) {
    const Eigen::Vector3d a = (g.P(i + 1) - 2 * g.P(i) + g.P(i - 1)) / (dt * dt);
    tracks[kAccel].values[k] = std::hypot(a.x(), a.y());
  }
  if (g.Same(i - 1, i + 2)) {
    const Eigen::Vector3d j = (g.P(i + 2) - 3 * g.P(i + 1) + 3 * g.P(i) - g.P(i - 1)) / (dt * dt * dt);
    tracks[kJerk].values[k] = j.norm();
  }
}

// Yaw, gimbal and lens rates from sample k-1 to k (none across a cut).
void MeasureRates(const Segments& g, const CameraSpec& c, size_t k, double dt, std::vector<LimitSeries>& tracks) {
  const long i = static_cast<long>(k);
  if (!g.Same(i - 1, i)) return;
  const auto& q = g.samples[k - 1];
  const auto& s = g.samples[k];
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

// The levels at sample k: gimbal pitch, altitude, nearest subject, the lens asked for, terrain clearance.
void MeasureLevels(const Trajectory& plan, size_t k, const LensRequest& r, double takeoff_up_m, const Ground* ground,
                   std::vector<LimitSeries>& tracks) {
  const auto& s = plan.samples[k];
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

}  // namespace

std::vector<LimitSeries> MeasureLimits(const Trajectory& plan, const std::vector<bool>& cut_before,
                                       const std::vector<LensRequest>& requests, const Ground* ground) {
  const auto& S = plan.samples;
  const size_t n = S.size();
  CINEPATH_CHECK(cut_before.size() == n);
  CINEPATH_CHECK(requests.empty() || requests.size() == n);
  const double dt = 1.0 / plan.frame_rate_hz;
  std::vector<LimitSeries> tracks = UnmeasuredTracks(plan.drone, plan.camera, n);
  const Segments segments(S, cut_before);
  const double takeoff_up_m = TakeoffUpM(plan, ground);
  for (size_t k = 0; k < n; ++k) {
    MeasureMotion(segments, k, dt, tracks);
    MeasureRates(segments, plan.camera, k, dt, tracks);
    const LensRequest r =
        requests.empty() ? LensRequest{S[k].focal_length_mm, S[k].focus_distance_m, S[k].f_number} : requests[k];
    MeasureLevels(plan, k, r, takeoff_up_m, ground, tracks);
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
