#include "optimizer/team_optimizer.h"

#include <algorithm>
#include <chrono>

#include "core/number_format.h"
#include "core/team_checks.h"
#include "optimizer/optimizer.h"

namespace cinepath::optimizer {
namespace {

const TrajectorySample& SampleAt(const Trajectory& plan, size_t k) {
  return plan.samples[std::min(k, plan.samples.size() - 1)];
}

// The other drones as drone `self` sees them, from `paths` (the flights' current plans). `half`: ask for
// half of a separation the planned paths miss (sweep 1).
std::vector<OtherDrone> OthersOf(const TeamPlan& team, const std::vector<Trajectory>& paths, size_t self, bool half) {
  const Trajectory& own = team.flights[self].plan;
  std::vector<OtherDrone> others;
  for (size_t j = 0; j < team.flights.size(); ++j) {
    if (j == self) continue;
    OtherDrone o;
    o.name = team.flights[j].name;
    o.body_radius_m = paths[j].drone.body_radius_m;
    o.camera = paths[j].camera;
    const double s = std::max(own.drone.min_separation_m, paths[j].drone.min_separation_m);
    for (size_t k = 0; k < own.samples.size(); ++k) {
      o.samples.push_back(SampleAt(paths[j], k));
      double target = s;
      if (half) {
        const double d = (own.samples[k].position_enu_m - o.samples.back().position_enu_m).norm();
        if (d < s) target = 0.5 * (d + s);
      }
      o.separation_m.push_back(target);
      const double t = own.samples[k].time_s;
      o.live.push_back(team.edit.empty() || LiveFlightAt(team, t) == static_cast<int>(j));
    }
    others.push_back(std::move(o));
  }
  return others;
}

Json ConflictsJson(const std::vector<TeamConflict>& conflicts) {
  Json out = Json::array();
  for (const auto& c : conflicts) {
    out.push_back({{"limit", c.limit},
                   {"drone", c.drone},
                   {"other", c.other},
                   {"start_time_s", RoundToDecimals(c.start_time_s, 9)},
                   {"end_time_s", RoundToDecimals(c.end_time_s, 9)},
                   {"worst_value", RoundToDecimals(c.worst_value, 6)},
                   {"unit", c.unit}});
  }
  return out;
}

}  // namespace

TeamOptimizeResult OptimizeTeam(const TeamOptimizeInput& input, const OptimizeOptions& options) {
  TeamOptimizeResult result;
  const TeamPlan& team = input.plan;
  auto one = [&](const Trajectory& plan, std::vector<OtherDrone> others, const std::string& name = "") {
    OptimizeInput in;
    in.plan = plan;
    in.plan_source = input.plan_source;
    in.mesh = input.mesh;
    in.scene_source = input.scene_source;
    for (const auto& s : plan.samples) {
      in.own_live.push_back(team.edit.empty() || LiveFlightAt(team, s.time_s) == team.FindFlight(name));
    }
    in.others = std::move(others);
    return OptimizePlan(in, options);
  };
  if (team.flights.size() == 1) {
    OptimizeResult r = one(team.flights[0].plan, {});
    result.plan = team;
    result.plan.flights[0].plan = std::move(r.plan);
    if (!team.single) CheckTeam(result.plan);
    result.report = std::move(r.report);
    result.failure = std::move(r.failure);
    return result;
  }

  TeamPlan before = team;
  CheckTeam(before);
  std::vector<Trajectory> paths;
  for (const auto& f : team.flights) paths.push_back(f.plan);

  // Sweep 1: each against the planned paths, half of each missing separation.
  std::vector<Trajectory> sweep1;
  for (size_t i = 0; i < team.flights.size(); ++i) {
    sweep1.push_back(one(team.flights[i].plan, OthersOf(team, paths, i, true), team.flights[i].name).plan);
  }
  // Sweep 2: in order, from the planned path, against the latest paths, the full separation.
  paths = sweep1;
  std::vector<OptimizeResult> results;
  for (size_t i = 0; i < team.flights.size(); ++i) {
    results.push_back(one(team.flights[i].plan, OthersOf(team, paths, i, false), team.flights[i].name));
    paths[i] = results.back().plan;
  }

  result.plan = team;
  for (size_t i = 0; i < team.flights.size(); ++i) result.plan.flights[i].plan = paths[i];
  CheckTeam(result.plan);

  Json record = Json::object();
  record["by"] = "cinepath optimize";
  record["quality"] = QualityName(options.quality);
  record["sweeps"] = 2;
  record["conflicts_before"] = before.team.conflicts.size();
  record["conflicts_after"] = result.plan.team.conflicts.size();
  result.plan.optimized = record;

  Json drones = Json::array();
  for (size_t i = 0; i < team.flights.size(); ++i) {
    Json r = results[i].report;
    r["drone"] = team.flights[i].name;
    drones.push_back(std::move(r));
    if (result.failure.empty() && !results[i].failure.empty()) {
      result.failure = "drone \"" + team.flights[i].name + "\": " + results[i].failure;
    }
  }
  Json team_report = Json::object();
  team_report["min_separation_m"] = result.plan.team.min_separation_m;
  team_report["conflicts_before"] = ConflictsJson(before.team.conflicts);
  team_report["conflicts_after"] = ConflictsJson(result.plan.team.conflicts);
  result.report = Json::object();
  result.report["team"] = std::move(team_report);
  result.report["drones"] = std::move(drones);

  if (result.failure.empty() && !result.plan.team.conflicts.empty()) {
    const TeamConflict& c = result.plan.team.conflicts.front();
    result.failure = c.limit + " between drones \"" + c.drone + "\" and \"" + c.other + "\" from " +
                     FormatShortest(c.start_time_s) + " s to " + FormatShortest(c.end_time_s) + " s (worst " +
                     FormatSignificant(c.worst_value) + " " + c.unit + ")";
  }
  return result;
}

}  // namespace cinepath::optimizer
