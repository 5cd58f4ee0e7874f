#include "optimizer/limit_guard.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <utility>

#include "core/number_format.h"
#include "optimizer/retime.h"
#include "optimizer/visibility_targets.h"
#include "scene/caster_ground.h"

namespace cinepath::optimizer {
namespace {

constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

LimitSeries Series(const std::string& limit, const std::string& unit, double limit_value, bool is_minimum, size_t n) {
  return {limit, unit, limit_value, is_minimum, std::vector<double>(n, kNotMeasured)};
}

// What would fix a limit that cannot be met, in a crew's words; `by` is how far it is broken.
std::string HintFor(const std::string& limit, double by) {
  static const std::map<std::string, std::string> kHints = {
      {"horizontal_speed", "the path is faster than the drone flies: a slower move, a longer shot or more deviation"},
      {"climb_rate", "the path climbs faster than the drone can: a longer shot or more deviation"},
      {"descent_rate", "the path descends faster than the drone can: a longer shot or more deviation"},
      {"horizontal_acceleration",
       "the path turns or brakes harder than the drone can: a wider path, a longer transition or more deviation"},
      {"jerk",
       "the path turns or brakes harder than the drone can: a wider path, a longer transition or more deviation"},
      {"yaw_rate", "the subject turns faster than the drone can yaw: a longer lens or a wider path"},
      {"gimbal_pitch_rate",
       "the subject crosses the frame vertically faster than the gimbal tilts: a longer lens or "
       "a wider path"},
      {"gimbal_pitch_min", "the subject is below the gimbal's tilt range: fly farther away or lower"},
      {"gimbal_pitch_max", "the subject is above the gimbal's tilt range: fly farther away or higher"},
      {"altitude_min", "the path is below the altitude band over the take-off point: raise the shot"},
      {"altitude_max", "the path is above the altitude band over the take-off point: lower the shot"},
      {"subject_distance", "the camera comes closer to an actor than the drone may: a wider path"},
      {"focal_length_rate", "the zoom is faster than the lens: a slower zoom or a longer shot"},
      {"focus_rate", "the focus pull is faster than the lens: a slower pull or a longer shot"},
      {"aperture_rate", "the aperture changes faster than the lens: a slower change or a longer shot"},
      {"mesh_crossing", "the path passes through the scene's surfaces: move its keyframes out of the mesh"},
      {"line_of_sight", "the scene hides the subject: more deviation, another angle or a higher path"},
  };
  if (const auto it = kHints.find(limit); it != kHints.end()) {
    // A rate: a shot in which no actor moves may also be flown slower (optimizer/retime.h).
    return TimeOrderOfLimit(limit) > 0 ? it->second + "; with no actor moving, \"optimize\": {\"retime\": true}"
                                       : it->second;
  }
  const std::string amount = FormatSignificant(by, 3);
  if (limit == "terrain_clearance") return "needs " + amount + " m more height over the terrain";
  if (limit == "mesh_clearance") return "needs " + amount + " m more distance from the scene's surfaces";
  if (limit == "max_deviation") return "needs " + amount + " m more deviation (max_deviation_m)";
  return "the lens cannot do this: another lens or framing";  // focal length, focus and f-number ranges
}

}  // namespace

LimitGuard::LimitGuard(const Trajectory& input, GuardSetup setup) : input_(input), setup_(std::move(setup)) {
  input_measure_ = Measure(input_);
  // The input's worst excess of each limit over each shot; frame by frame for sight and crossings.
  const size_t n = input_.samples.size();
  for (const auto& series : input_measure_) {
    std::vector<double>& allowed = allowed_.emplace_back(n, 0.0);
    for (size_t k = 0; k < n; ++k) allowed[k] = series.Excess(k);
    if (series.limit == "line_of_sight" || series.limit == "mesh_crossing") continue;
    std::map<int, double> worst;  // per shot
    for (size_t k = 0; k < n; ++k) {
      const int shot = setup_.shot_of_sample[k];
      if (shot >= 0) worst[shot] = std::max(worst[shot], allowed[k]);
    }
    for (size_t k = 0; k < n; ++k) {
      if (setup_.shot_of_sample[k] >= 0) allowed[k] = worst[setup_.shot_of_sample[k]];
    }
  }
}

LimitMeasure LimitGuard::Measure(const Trajectory& plan) const {
  std::unique_ptr<scene::CasterGround> ground;
  if (setup_.caster) ground = std::make_unique<scene::CasterGround>(*setup_.caster, setup_.scene_source);
  LimitMeasure m = MeasureLimits(plan, setup_.cut_before, {}, ground.get());
  const size_t n = plan.samples.size();
  const auto position = [&](size_t k) -> const Eigen::Vector3d& { return plan.samples[k].position_enu_m; };

  // How far past each shot's max_deviation_m the path has left the plan as given (negative: within it).
  auto& deviation = m.emplace_back(Series("max_deviation", "m", 0.0, false, n));
  for (size_t k = 0; k < n; ++k) {
    deviation.values[k] = (position(k) - setup_.origin_enu_m[k]).norm() - setup_.max_deviation_m[k];
  }
  if (!setup_.caster) return m;
  auto& clearance = m.emplace_back(Series("mesh_clearance", "m", setup_.clearance_margin_m, true, n));
  auto& crossing = m.emplace_back(Series("mesh_crossing", "", 0.0, false, n));
  auto& sight = m.emplace_back(Series("line_of_sight", "", 0.0, false, n));
  for (size_t k = 0; k < n; ++k) {
    // The distance to the nearest surface, exactly (a closest-point query; the winding plays no part).
    if (setup_.surface) {
      if (const auto c = setup_.surface->Closest(position(k))) clearance.values[k] = c->distance_m;
    }
    // The path from the previous sample through a surface (1) or not (0); nothing is flown across a cut.
    if (k > 0 && !setup_.cut_before[k]) {
      const Eigen::Vector3d step = position(k) - position(k - 1);
      const double length = step.norm();
      crossing.values[k] =
          length > 1e-12 && setup_.caster->Occluded(position(k - 1), step / length, 0.0, length) ? 1.0 : 0.0;
    }
    // The subject hidden (1) or seen (0).
    if (setup_.aim_enu_m[k]) {
      sight.values[k] = LineOfSightBlocked(*setup_.caster, position(k), *setup_.aim_enu_m[k]) ? 1.0 : 0.0;
    }
  }
  return m;
}

std::vector<std::string> LimitGuard::WorseThanInput(const LimitMeasure& candidate) const {
  std::vector<std::string> worse;
  for (size_t i = 0; i < candidate.size(); ++i) {
    const LimitSeries& c = candidate[i];
    const double slack = 1e-9 * std::max(1.0, std::fabs(c.limit_value));
    for (size_t k = 0; k < c.values.size(); ++k) {
      if (c.Excess(k) > allowed_[i][k] + slack) {
        worse.push_back(c.limit);
        break;
      }
    }
  }
  return worse;
}

std::vector<bool> LimitGuard::WorseSamples(const LimitMeasure& candidate) const {
  std::vector<bool> worse(input_.samples.size(), false);
  for (size_t i = 0; i < candidate.size(); ++i) {
    const LimitSeries& c = candidate[i];
    const double slack = 1e-9 * std::max(1.0, std::fabs(c.limit_value));
    for (size_t k = 0; k < c.values.size() && k < worse.size(); ++k) {
      if (c.Excess(k) > allowed_[i][k] + slack) worse[k] = true;
    }
  }
  return worse;
}

GuardedPlan KeepNeverWorse(const LimitGuard& guard, const std::function<Trajectory(double)>& at, int steps) {
  const std::vector<int> one_group(guard.input().empty() ? 0 : guard.input().front().values.size(), 0);
  return KeepNeverWorseByGroup(
      guard, one_group, [&](const std::vector<double>& a) { return at(a[0]); }, steps);
}

GuardedPlan KeepNeverWorseByGroup(const LimitGuard& guard, const std::vector<int>& group_of_sample,
                                  const std::function<Trajectory(const std::vector<double>&)>& at, int steps) {
  const int groups =
      group_of_sample.empty() ? 1 : *std::max_element(group_of_sample.begin(), group_of_sample.end()) + 1;
  std::vector<double> alpha(groups, 1.0);
  const auto finish = [&](GuardedPlan out) {
    out.group_alpha = alpha;
    out.alpha = *std::min_element(alpha.begin(), alpha.end());
    return out;
  };
  GuardedPlan whole;
  whole.plan = at(alpha);
  whole.measure = guard.Measure(whole.plan);
  whole.raw_broke = guard.WorseThanInput(whole.measure);
  if (whole.raw_broke.empty()) return finish(std::move(whole));
  // The groups with a sample worse start from their input (alpha 0); the others keep their whole change.
  const std::vector<bool> worse = guard.WorseSamples(whole.measure);
  std::vector<bool> cut(groups, groups == 1);
  for (size_t k = 0; k < worse.size() && k < group_of_sample.size(); ++k) {
    if (worse[k]) cut[group_of_sample[k]] = true;
  }
  for (int g = 0; g < groups; ++g) {
    if (cut[g]) alpha[g] = 0;
  }
  GuardedPlan best{at(alpha), 0.0, {}, {}, {}};
  best.measure = groups == 1 ? guard.input() : guard.Measure(best.plan);
  if (!guard.WorseThanInput(best.measure).empty()) {  // a limit across groups: every group from its input
    std::fill(alpha.begin(), alpha.end(), 0.0);
    best = GuardedPlan{at(alpha), 0.0, {}, {}, guard.input()};
    std::fill(cut.begin(), cut.end(), true);
  }
  // Bisection on [lo, hi] per group cut, lo always never worse.
  for (int g = 0; g < groups; ++g) {
    if (!cut[g]) continue;
    double lo = 0, hi = 1;
    for (int i = 0; i < steps; ++i) {
      const double mid = 0.5 * (lo + hi);
      alpha[g] = mid;
      Trajectory plan = at(alpha);
      LimitMeasure measure = guard.Measure(plan);
      if (guard.WorseThanInput(measure).empty()) {
        lo = mid;
        best.plan = std::move(plan);
        best.measure = std::move(measure);
      } else {
        hi = mid;
      }
    }
    alpha[g] = lo;
  }
  best.raw_broke = std::move(whole.raw_broke);
  return finish(std::move(best));
}

Json StillBroken(const LimitMeasure& measure, const Trajectory& plan, std::string* first_message) {
  std::vector<std::pair<FeasibilityViolation, double>> ranges;  // with how far it is broken
  for (const auto& series : measure) {
    for (const auto& v : ViolationsOf(series, plan)) ranges.emplace_back(v, std::fabs(v.worst_value - v.limit_value));
  }
  std::stable_sort(ranges.begin(), ranges.end(),
                   [](const auto& a, const auto& b) { return a.first.start_time_s < b.first.start_time_s; });
  Json out = Json::array();
  first_message->clear();
  for (const auto& [v, by] : ranges) {
    Json j = Json::object();
    j["limit"] = v.limit;
    j["shot"] = v.shot;
    j["start_time_s"] = v.start_time_s;
    j["end_time_s"] = v.end_time_s;
    j["worst"] = RoundToDecimals(v.worst_value, 6);
    j["limit_value"] = RoundToDecimals(v.limit_value, 6);
    j["unit"] = v.unit;
    j["by"] = RoundToDecimals(by, 6);
    j["hint"] = HintFor(v.limit, by);
    out.push_back(j);
    if (first_message->empty()) {
      const std::string unit = v.unit.empty() ? "" : " " + v.unit;
      *first_message = v.limit + " in shot \"" + v.shot + "\" from " + FormatShortest(v.start_time_s) + " s to " +
                       FormatShortest(v.end_time_s) + " s (worst " + FormatSignificant(v.worst_value) + unit +
                       ", limit " + FormatSignificant(v.limit_value) + unit + "): " + HintFor(v.limit, by);
    }
  }
  return out;
}

}  // namespace cinepath::optimizer
