#include "optimizer/retime.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "core/angles.h"
#include "core/feasibility.h"
#include "core/geodesy.h"
#include "core/local_level.h"
#include "core/rotation.h"
#include "optimizer/plan_samples.h"

namespace cinepath::optimizer {
namespace {

constexpr double kSlopePerSecond = 0.5;  // the slow-down changes by at most this a second
constexpr double kSmoothingS = 0.25;     // box filter, applied twice
constexpr double kNeedMargin = 1.02;     // aim a little inside the limit
constexpr int kRounds = 10;              // warp, measure, raise the need where still broken
constexpr int kShrinkSteps = 6;          // then the least fraction of that slow-down that does as well
constexpr double kActorStillM = 1e-6;
constexpr double kMaxSlowDown = 20;  // no part of a shot flown more than this much slower    // an actor that moves
                                     // less than this in a shot stands still

// The samples [begin, end) of one shot.
struct Range {
  size_t begin = 0, end = 0;
  size_t size() const { return end - begin; }
};

Range RangeOf(const Trajectory& plan, const std::string& shot) {
  Range r{plan.samples.size(), plan.samples.size()};
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    if (plan.samples[k].shot != shot) continue;
    if (r.begin == plan.samples.size()) r.begin = k;
    r.end = k + 1;
  }
  return r;
}

// One coordinate as a cubic spline through its values at u = 0, 1, ..., n-1, its second derivative at
// each end the path's own there (extrapolated from the second differences of the end samples), not zero: a natural end
// would bend the last interval and put a jerk into the end of the shot that the plan does not have.
class CubicThroughSamples {
 public:
  explicit CubicThroughSamples(std::vector<double> y) : y_(std::move(y)), m_(y_.size(), 0.0) {
    const size_t n = y_.size();
    if (n < 3) return;
    const auto second_difference = [&](size_t i) { return y_[i - 1] - 2 * y_[i] + y_[i + 1]; };
    // Extrapolated from the two nearest second differences (centred on samples 1 and 2).
    m_[0] = n >= 4 ? 2 * second_difference(1) - second_difference(2) : second_difference(1);
    m_[n - 1] = n >= 4 ? 2 * second_difference(n - 2) - second_difference(n - 3) : second_difference(n - 2);
    // Second derivatives: m[i-1] + 4 m[i] + m[i+1] = 6 (y[i-1] - 2 y[i] + y[i+1]), the ends known.
    std::vector<double> c(n, 0.0), d(n, 0.0);
    d[0] = m_[0];
    for (size_t i = 1; i + 1 < n; ++i) {
      const double rhs = 6 * (y_[i - 1] - 2 * y_[i] + y_[i + 1]);
      const double denom = 4 - c[i - 1];
      c[i] = 1 / denom;
      d[i] = (rhs - d[i - 1]) / denom;
    }
    for (size_t i = n - 2; i >= 1; --i) m_[i] = d[i] - c[i] * m_[i + 1];
  }
  double At(size_t k, double x) const {  // u = k + x, x in [0, 1]
    if (k + 1 >= y_.size()) return y_.back();
    const double a = 1 - x;
    return a * y_[k] + x * y_[k + 1] + ((a * a * a - a) * m_[k] + (x * x * x - x) * m_[k + 1]) / 6;
  }

 private:
  std::vector<double> y_, m_;
};

// The new clock of one shot: the slow-down at each planned sample and the time reached there.
struct Warp {
  std::vector<double> slow;   // s(u) at u = 0..n-1, linear between
  std::vector<double> tau_s;  // time from the shot's start at u = 0..n-1
  size_t new_intervals = 0;   // frames - 1 of the retimed shot
  double dt = 0;

  // The shot-local time at progress u.
  double TimeAt(double u) const {
    u = std::clamp(u, 0.0, static_cast<double>(slow.size() - 1));
    const size_t k = std::min(static_cast<size_t>(u), slow.size() - 2);
    const double x = u - k;
    return tau_s[k] + dt * (slow[k] * x + (slow[k + 1] - slow[k]) * x * x / 2);
  }
  // The progress at shot-local time t (the inverse of TimeAt).
  double ProgressAt(double t) const {
    const size_t n = slow.size();
    if (t <= 0) return 0;
    if (t >= tau_s[n - 1]) return static_cast<double>(n - 1);
    const size_t k = std::upper_bound(tau_s.begin(), tau_s.end(), t) - tau_s.begin() - 1;
    const double a = dt * (slow[k + 1] - slow[k]) / 2, b = dt * slow[k], r = t - tau_s[k];
    const double x = 2 * r / (b + std::sqrt(std::max(0.0, b * b + 4 * a * r)));
    return k + std::clamp(x, 0.0, 1.0);
  }
};

// Shapes the need at each sample into a slow-down: spread to the neighbours by at most `step[k]` from
// sample k to k + 1, at most `start_cap` / `end_cap` at the ends (the caps growing by the same steps inward),
// smoothed, then scaled inside so that the shot ends on a whole frame.
Warp MakeWarp(const std::vector<double>& need, const std::vector<double>& step, double start_cap, double end_cap,
              double dt) {
  const size_t n = need.size();
  std::vector<double> s(n);
  for (size_t k = 0; k < n; ++k) s[k] = std::max(1.0, need[k]);
  for (size_t k = 1; k < n; ++k) s[k] = std::max(s[k], s[k - 1] - step[k - 1]);
  for (size_t k = n - 1; k-- > 0;) s[k] = std::max(s[k], s[k + 1] - step[k]);
  std::vector<double> from_start(n, start_cap), from_end(n, end_cap);  // the caps, grown step by step
  for (size_t k = 1; k < n; ++k) from_start[k] = from_start[k - 1] + step[k - 1];
  for (size_t k = n - 1; k-- > 0;) from_end[k] = from_end[k + 1] + step[k];
  const auto cap = [&] {
    for (size_t k = 0; k < n; ++k) s[k] = std::min({s[k], from_start[k], from_end[k]});
  };
  cap();
  const int half = std::max(1, static_cast<int>(std::lround(kSmoothingS / dt / 2)));
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<double> out(n);
    for (size_t k = 0; k < n; ++k) {
      double sum = 0;
      for (int d = -half; d <= half; ++d) {
        const long i = std::clamp<long>(static_cast<long>(k) + d, 0, static_cast<long>(n) - 1);
        sum += s[i];
      }
      out[k] = sum / (2 * half + 1);
    }
    s = std::move(out);
  }
  cap();
  Warp w;
  w.dt = dt;
  const auto integrate = [&] {
    w.tau_s.assign(n, 0.0);
    for (size_t k = 1; k < n; ++k) w.tau_s[k] = w.tau_s[k - 1] + dt * (s[k - 1] + s[k]) / 2;
  };
  integrate();
  w.new_intervals = static_cast<size_t>(std::ceil(w.tau_s.back() / dt - 1e-6));
  double extra_area = 0;  // the time the part above 1 adds
  for (size_t k = 1; k < n; ++k) extra_area += dt * (s[k - 1] + s[k] - 2) / 2;
  if (extra_area > 0) {
    const double grow = (w.new_intervals * dt - w.tau_s.back()) / extra_area;
    for (double& v : s) v = 1 + (v - 1) * (1 + grow);
    integrate();
  }
  w.slow = std::move(s);
  return w;
}

double Lerp(double a, double b, double x) { return a + (b - a) * x; }

// The shot's samples flown on the warp's clock; `progress` gets each new sample's u.
std::vector<TrajectorySample> ResampleShot(const Trajectory& plan, Range range, const Warp& warp,
                                           std::vector<double>* progress) {
  const size_t n = range.size();
  std::vector<CubicThroughSamples> axes;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> y(n);
    for (size_t k = 0; k < n; ++k) y[k] = plan.samples[range.begin + k].position_enu_m[axis];
    axes.emplace_back(std::move(y));
  }
  std::optional<EnuFrame> frame;
  if (plan.origin) frame.emplace(*plan.origin);
  const double t0 = plan.samples[range.begin].time_s;
  std::vector<TrajectorySample> out;
  progress->clear();
  for (size_t j = 0; j <= warp.new_intervals; ++j) {
    const double u = j == warp.new_intervals ? static_cast<double>(n - 1) : warp.ProgressAt(j * warp.dt);
    progress->push_back(u);
    const size_t k = std::min(static_cast<size_t>(u), n >= 2 ? n - 2 : 0);
    const double x = n >= 2 ? u - k : 0.0;
    const TrajectorySample& a = plan.samples[range.begin + k];
    const TrajectorySample& b = plan.samples[range.begin + std::min(k + 1, n - 1)];
    TrajectorySample s = x < 0.5 ? a : b;  // the shot's name, the subjects in frame
    s.time_s = t0 + j * warp.dt;
    for (int axis = 0; axis < 3; ++axis) s.position_enu_m[axis] = axes[axis].At(k, x);
    s.world_from_camera = a.world_from_camera.slerp(x, b.world_from_camera).normalized();
    const bool nose_on_camera = a.gimbal_yaw_deg == 0 && b.gimbal_yaw_deg == 0;
    const double heading =
        NormalizeDeg360(a.drone_heading_deg + x * AngleDiffDeg(a.drone_heading_deg, b.drone_heading_deg));
    SetLocalAngles(frame ? &*frame : nullptr, s, nose_on_camera ? std::numeric_limits<double>::quiet_NaN() : heading);
    s.focal_length_mm = std::exp(Lerp(std::log(a.focal_length_mm), std::log(b.focal_length_mm), x));
    const double dioptre = Lerp(1 / a.focus_distance_m, 1 / b.focus_distance_m, x);  // 1 / inf = 0
    s.focus_distance_m = dioptre > 0 ? 1 / dioptre : std::numeric_limits<double>::infinity();
    s.f_number = std::exp(Lerp(std::log(a.f_number), std::log(b.f_number), x));
    s.shutter_s = Lerp(a.shutter_s, b.shutter_s, x);
    out.push_back(std::move(s));
  }
  return out;
}

// The plan with shot `index`'s samples replaced by `samples` (its warp `warp`), everything after later.
Trajectory Splice(const Trajectory& plan, size_t index, Range range, std::vector<TrajectorySample> samples,
                  const std::vector<double>& progress, const Warp& warp) {
  Trajectory out = plan;
  const double added_s = (samples.size() - range.size()) * warp.dt;
  const double t0 = plan.samples[range.begin].time_s;
  out.samples.assign(plan.samples.begin(), plan.samples.begin() + range.begin);
  for (auto& s : samples) out.samples.push_back(std::move(s));
  for (size_t k = range.end; k < plan.samples.size(); ++k) {
    out.samples.push_back(plan.samples[k]);
    out.samples.back().time_s += added_s;
  }
  for (size_t a = 0; a < plan.subjects.size(); ++a) {
    const auto& before = plan.subjects[a].positions_enu_m;
    auto& after = out.subjects[a].positions_enu_m;
    after.assign(before.begin(), before.begin() + range.begin);
    for (double u : progress) {
      const size_t k = std::min(static_cast<size_t>(u), range.size() >= 2 ? range.size() - 2 : 0);
      const double x = range.size() >= 2 ? u - k : 0.0;
      const size_t i = range.begin + k, i1 = range.begin + std::min(k + 1, range.size() - 1);
      after.push_back(before[i] + x * (before[i1] - before[i]));
    }
    after.insert(after.end(), before.begin() + range.end, before.end());
  }
  const auto retimed = [&](double local_s) { return warp.TimeAt(local_s / warp.dt); };
  ShotSpan& span = out.shots[index];
  span.end_time_s += added_s;
  for (RackIntent& r : span.intent.rack) {
    const double at = retimed(r.at_s);
    r.duration_s = std::max(1e-3, retimed(r.at_s + r.duration_s) - at);
    r.at_s = at;
  }
  for (size_t j = index + 1; j < out.shots.size(); ++j) {
    out.shots[j].start_time_s += added_s;
    out.shots[j].end_time_s += added_s;
  }
  std::map<std::string, size_t> order;
  for (size_t j = 0; j < plan.shots.size(); ++j) order[plan.shots[j].name] = j;
  for (Keyframe& key : out.keyframes) {
    const auto it = order.find(key.shot);
    if (it == order.end()) continue;
    if (it->second == index) key.time_s = t0 + retimed(key.time_s - t0);
    if (it->second > index) key.time_s += added_s;
  }
  return out;
}

struct Measured {
  std::vector<LimitSeries> series;
  std::map<std::pair<std::string, std::string>, double> worst;  // (shot, limit) -> largest excess
};

Measured Measure(const Trajectory& plan, const Ground* ground) {
  Measured m;
  m.series = MeasureLimits(plan, SplitPlan(plan, 1.0, "plan", false).cut_before, {}, ground);
  for (const auto& series : m.series) {
    for (size_t k = 0; k < series.values.size(); ++k) {
      double& w = m.worst[{plan.samples[k].shot, series.limit}];
      w = std::max(w, series.Excess(k));
    }
  }
  return m;
}

// The (shot, limit) pairs `after` breaks by more than `before` (of the levels only, with `levels_only`).
std::vector<std::string> Worse(const Measured& before, const Measured& after, bool levels_only) {
  std::vector<std::string> out;
  for (const auto& [key, excess] : after.worst) {
    if (levels_only && TimeOrderOfLimit(key.second) > 0) continue;
    const auto it = before.worst.find(key);
    const double was = it == before.worst.end() ? 0.0 : it->second;
    if (excess > was * (1 + 1e-9) + 1e-12) out.push_back(key.second + " in shot \"" + key.first + "\"");
  }
  return out;
}

// The frames of the whole plan at which some rate limit is broken.
size_t RateBrokenFrames(const Measured& m) {
  std::vector<bool> broken;
  for (const auto& series : m.series) {
    if (TimeOrderOfLimit(series.limit) == 0) continue;
    broken.resize(series.values.size(), false);
    for (size_t k = 0; k < series.values.size(); ++k) broken[k] = broken[k] || series.Excess(k) > 0;
  }
  return std::count(broken.begin(), broken.end(), true);
}

// The need at each sample of `range` (u = sample index within it), from the rate limits broken there:
// (value / limit)^(1 / order). Counts the samples broken and names the limits.
size_t NeedsOf(const Measured& m, Range range, std::vector<double>* need, std::vector<std::string>* limits) {
  std::vector<double> unused;
  if (!need) need = &unused;
  need->assign(range.size(), 1.0);
  std::vector<bool> broken(range.size(), false);
  for (const auto& series : m.series) {
    const int order = TimeOrderOfLimit(series.limit);
    if (order == 0) continue;
    for (size_t i = 0; i < range.size(); ++i) {
      if (series.Excess(range.begin + i) == 0) continue;
      const double ratio = std::min(series.values[range.begin + i] / series.limit_value, 1e6);
      (*need)[i] = std::max((*need)[i], std::pow(ratio, 1.0 / order) * kNeedMargin);
      broken[i] = true;
      if (limits && std::find(limits->begin(), limits->end(), series.limit) == limits->end())
        limits->push_back(series.limit);
    }
  }
  return std::count(broken.begin(), broken.end(), true);
}

bool ActorsStill(const Trajectory& plan, Range range, std::string* moving) {
  for (const auto& actor : plan.subjects) {
    for (size_t k = range.begin + 1; k < range.end; ++k) {
      if ((actor.positions_enu_m[k] - actor.positions_enu_m[range.begin]).norm() > kActorStillM) {
        *moving = actor.name;
        return false;
      }
    }
  }
  return true;
}

// The largest slow-down at an end the shot shares with a continuous neighbour (samples a, b across the
// join): the pace may change there only as far as the velocity's jump stays within half of what the
// drone's acceleration allows in one frame (a shot that ends at rest may change its pace freely there).
// The jerk of such a jump may still break the limit for a frame or two: optimize's second ladder smooths
// it, and the result is checked against the plan as given (optimizer.cc).
double EndCap(const Trajectory& plan, size_t a, size_t b) {
  const double dt = 1.0 / plan.frame_rate_hz;
  const double speed_m_s = (plan.samples[b].position_enu_m - plan.samples[a].position_enu_m).norm() / dt;
  const double jump_m_s = 0.5 * plan.drone.max_acceleration_m_s2 * dt;
  return speed_m_s <= jump_m_s ? std::numeric_limits<double>::infinity() : 1 / (1 - jump_m_s / speed_m_s);
}

// One shot: warp, measure, raise the need where a rate is still broken; the warp that leaves the fewest frames
// of the plan breaking a rate, never worse in any level.
std::optional<RetimedShot> RetimeOne(Trajectory* plan, size_t index, const std::vector<bool>& cut_before,
                                     const Ground* ground) {
  const ShotSpan& span = plan->shots[index];
  const Range range = RangeOf(*plan, span.name);
  if (range.size() < 2) return std::nullopt;
  const Measured before = Measure(*plan, ground);
  RetimedShot report;
  report.shot = span.name;
  std::vector<double> need;
  report.broken_samples_before = NeedsOf(before, range, &need, &report.limits);
  if (report.broken_samples_before == 0) return std::nullopt;
  const double dt = 1.0 / plan->frame_rate_hz;
  const double start_cap = range.begin > 0 && !cut_before[range.begin] ? EndCap(*plan, range.begin - 1, range.begin)
                                                                       : std::numeric_limits<double>::infinity();
  const double end_cap = range.end < plan->samples.size() && !cut_before[range.end]
                             ? EndCap(*plan, range.end - 1, range.end)
                             : std::numeric_limits<double>::infinity();
  // How fast the slow-down may change from one sample to the next: kSlopePerSecond, or faster where the
  // planned speed is low, as long as the acceleration the change of pace adds (the planned speed times the
  // change of 1 / s a second) stays within a quarter of the drone's.
  std::vector<double> steps(range.size(), kSlopePerSecond * dt);
  for (size_t k = 0; k + 1 < range.size(); ++k) {
    const auto& p = plan->samples;
    const double speed_m_s = (p[range.begin + k + 1].position_enu_m - p[range.begin + k].position_enu_m).norm() / dt;
    steps[k] = std::max(steps[k], 0.25 * plan->drone.max_acceleration_m_s2 * dt / std::max(speed_m_s, 1e-9));
  }
  std::optional<Trajectory> best;
  size_t best_broken = report.broken_samples_before, best_frames = RateBrokenFrames(before);
  Warp best_warp;
  std::vector<double> best_need;
  // One try: the warp of `try_need`, kept when it leaves fewer frames over a rate (or as few, in less time).
  const auto attempt = [&](const std::vector<double>& try_need, std::vector<double>* still,
                           std::vector<double>* progress) {
    const Warp warp = MakeWarp(try_need, steps, start_cap, end_cap, dt);
    std::vector<TrajectorySample> samples = ResampleShot(*plan, range, warp, progress);
    Trajectory candidate = Splice(*plan, index, range, std::move(samples), *progress, warp);
    const Measured after = Measure(candidate, ground);
    const size_t broken = NeedsOf(after, RangeOf(candidate, span.name), still, nullptr);
    const size_t frames = RateBrokenFrames(after);
    const bool shorter = best && warp.new_intervals < best_warp.new_intervals;
    if (Worse(before, after, true).empty() && (frames < best_frames || (frames == best_frames && shorter))) {
      best_frames = frames;
      best_broken = broken;
      best = std::move(candidate);
      best_warp = warp;
      best_need = try_need;
    }
    return std::make_pair(broken, warp);
  };
  for (int round = 0; round < kRounds; ++round) {
    std::vector<double> still, progress;
    const auto [broken, warp] = attempt(need, &still, &progress);
    if (broken == 0) break;
    // Raise the need at the planned samples the broken new ones fall between.
    for (size_t j = 0; j < still.size(); ++j) {
      if (still[j] <= 1.0) continue;
      const size_t k = static_cast<size_t>(progress[j]);
      for (size_t i = k; i <= std::min(k + 1, need.size() - 1); ++i)
        need[i] = std::min(kMaxSlowDown, std::max(need[i], warp.slow[i]) * std::sqrt(still[j]));
    }
  }
  if (!best) return std::nullopt;
  // The rounds raise the need by steps and may overshoot: the least fraction of the kept slow-down (above 1)
  // that does as well, by bisection.
  const std::vector<double> kept_need = best_need;
  double lo = 0, hi = 1;
  for (int step = 0; step < kShrinkSteps; ++step) {
    const double mid = (lo + hi) / 2;
    std::vector<double> scaled(kept_need.size()), still, progress;
    for (size_t i = 0; i < scaled.size(); ++i) scaled[i] = 1 + mid * (std::max(1.0, kept_need[i]) - 1);
    const size_t frames_before = best_frames, length_before = best_warp.new_intervals;
    attempt(scaled, &still, &progress);
    const bool as_good = best_frames < frames_before || best_warp.new_intervals < length_before;
    (as_good ? hi : lo) = mid;
  }
  report.duration_before_s = (range.size() - 1) * dt;
  report.duration_after_s = best_warp.new_intervals * dt;
  report.slowest_factor = *std::max_element(best_warp.slow.begin(), best_warp.slow.end());
  report.broken_samples_after = best_broken;
  *plan = std::move(*best);
  return report;
}

}  // namespace

std::vector<std::string> WorseThan(const Trajectory& before, const Trajectory& after, const Ground* ground) {
  return Worse(Measure(before, ground), Measure(after, ground), false);
}

int TimeOrderOfLimit(const std::string& limit) {
  static const std::map<std::string, int> kOrders = {{"horizontal_speed", 1},
                                                     {"climb_rate", 1},
                                                     {"descent_rate", 1},
                                                     {"yaw_rate", 1},
                                                     {"gimbal_pitch_rate", 1},
                                                     {"focal_length_rate", 1},
                                                     {"focus_rate", 1},
                                                     {"aperture_rate", 1},
                                                     {"horizontal_acceleration", 2},
                                                     {"jerk", 3}};
  const auto it = kOrders.find(limit);
  return it == kOrders.end() ? 0 : it->second;
}

RetimeResult RetimeShots(const Trajectory& plan, const Ground* ground, const std::set<std::string>* only) {
  RetimeResult result;
  result.plan = plan;
  const double length_before_s = plan.samples.empty() ? 0 : plan.samples.back().time_s - plan.samples[0].time_s;
  std::vector<std::string> asked;
  for (size_t index = 0; index < plan.shots.size(); ++index) {
    const std::string& name = plan.shots[index].name;
    if (!plan.shots[index].intent.retime || (only && !only->count(name))) continue;
    asked.push_back(name);
    std::string moving;
    if (!ActorsStill(result.plan, RangeOf(result.plan, name), &moving)) {
      result.notes.push_back("shot \"" + name + "\" is not retimed: actor \"" + moving + "\" moves in it");
      continue;
    }
    const std::vector<bool> cut_before = SplitPlan(result.plan, 1.0, "plan", false).cut_before;
    if (auto shot = RetimeOne(&result.plan, index, cut_before, ground)) {
      result.shots.push_back(*shot);
    } else if (Measured m = Measure(result.plan, ground); NeedsOf(m, RangeOf(result.plan, name), nullptr, nullptr)) {
      result.notes.push_back("shot \"" + name +
                             "\" is not retimed: no slower pace left fewer frames over a rate limit without breaking "
                             "a level (a rate broken at a continuous join needs the neighbouring shot slower too)");
    }
  }
  const Measured after = Measure(result.plan, ground);
  for (const std::string& name : asked)
    result.rate_broken_samples += NeedsOf(after, RangeOf(result.plan, name), nullptr, nullptr);
  if (!result.shots.empty()) {
    result.plan.feasibility =
        CheckFeasibility(result.plan, SplitPlan(result.plan, 1.0, "plan", false).cut_before, {}, ground);
    result.added_s = result.plan.samples.back().time_s - result.plan.samples[0].time_s - length_before_s;
  }
  return result;
}

}  // namespace cinepath::optimizer
