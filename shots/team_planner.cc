#include "shots/team_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/number_format.h"
#include "core/team_checks.h"
#include "shots/lens_track.h"

namespace cinepath::shots {
namespace {

// One drone's part of the list: its shots, camera and aircraft.
ShotList DroneList(const ShotList& list, size_t drone) {
  ShotList view;
  view.source = list.source;
  view.origin = list.origin;
  view.frame_rate_hz = list.frame_rate_hz;
  view.camera = list.drones[drone].camera;
  view.drone = list.drones[drone].drone;
  view.actors = list.actors;
  view.ground = list.ground;
  for (const auto& s : list.shots) {
    if (s.drone == static_cast<int>(drone)) view.shots.push_back(s);
  }
  return view;
}

double TotalDurationS(const ShotList& view) {
  double total = 0;
  for (const auto& s : view.shots) total += s.duration_s;
  return total;
}

// The shot of `view` that runs at time t (the last one when t is past the end).
const ShotSpec& ShotAt(const ShotList& view, double t) {
  double start = 0;
  for (const auto& s : view.shots) {
    if (t < start + s.duration_s - 1e-12) return s;
    start += s.duration_s;
  }
  return view.shots.back();
}

std::string EditPath(const ShotList& list, size_t cut, const char* key) {
  return list.source + ": edit[" + std::to_string(cut) + "]." + key;
}

// The sample nearest to t (the flight holds its last sample after its end).
const TrajectorySample& SampleNear(const Trajectory& plan, double t) {
  const double k = std::round(t * plan.frame_rate_hz);
  const size_t i = static_cast<size_t>(std::clamp(k, 0.0, static_cast<double>(plan.samples.size() - 1)));
  return plan.samples[i];
}

}  // namespace

TeamPlan PlanTeam(const ShotList& list, const PlanOptions& options) {
  if (list.drones.empty()) {  // one drone: a team of one, as a version 1 plan reads (core/plan_file.h)
    TeamPlan team;
    team.single = true;
    Trajectory plan = PlanShots(list, options);
    team.origin = plan.origin;
    team.frame_rate_hz = plan.frame_rate_hz;
    team.team.min_separation_m = plan.drone.min_separation_m;
    team.flights.push_back({list.drone.name, std::nullopt, std::move(plan)});
    return team;
  }
  std::vector<ShotList> views;
  double longest = 0;
  for (size_t d = 0; d < list.drones.size(); ++d) {
    views.push_back(DroneList(list, d));
    longest = std::max(longest, TotalDurationS(views.back()));
  }

  // Matched focus: the incoming camera focuses on the outgoing shot's subject while it is live.
  std::vector<std::vector<FocusOverride>> overrides(list.drones.size());
  for (size_t c = 0; c < list.edit.size(); ++c) {
    const EditCut& cut = list.edit[c];
    if (cut.at_s > longest + 1e-9) {
      throw InputError(EditPath(list, c, "at_s") + ": cuts after the plan ends (" + FormatShortest(longest) + " s)");
    }
    if (!cut.match_focus) continue;
    const size_t from = static_cast<size_t>(list.FindDrone(list.edit[c - 1].drone));
    const size_t to = static_cast<size_t>(list.FindDrone(cut.drone));
    const ShotSpec& outgoing = ShotAt(views[from], cut.at_s);
    if (outgoing.subject < 0) {
      throw InputError(EditPath(list, c, "match_focus") + ": the outgoing shot \"" + outgoing.name + "\" of drone \"" +
                       list.drones[from].name + "\" has no subject to match");
    }
    const double end_s = c + 1 < list.edit.size() ? list.edit[c + 1].at_s : longest;
    overrides[to].push_back({.start_s = cut.at_s, .end_s = end_s, .actor = outgoing.subject});
  }

  TeamPlan team;
  team.origin = list.origin;
  team.frame_rate_hz = list.frame_rate_hz;
  team.edit = list.edit;
  for (size_t d = 0; d < list.drones.size(); ++d) {
    PlanOptions drone_options = options;
    drone_options.focus_overrides = overrides[d];
    team.flights.push_back({list.drones[d].name, list.drones[d].home_enu_m, PlanShots(views[d], drone_options)});
  }

  // What the matched cuts give: each camera's focus error on the shared subject at the cut.
  for (size_t c = 1; c < team.edit.size(); ++c) {
    if (!team.edit[c].match_focus) continue;
    const DroneFlight& from = team.flights[static_cast<size_t>(team.FindFlight(team.edit[c - 1].drone))];
    const DroneFlight& to = team.flights[static_cast<size_t>(team.FindFlight(team.edit[c].drone))];
    const double t = team.edit[c].at_s;
    const ShotSpec& outgoing = ShotAt(views[static_cast<size_t>(list.FindDrone(from.name))], t);
    const Actor& subject = list.actors[static_cast<size_t>(outgoing.subject)];
    auto error = [&](const TrajectorySample& s) {
      const Eigen::Vector3d v = subject.AimPointAt(t) - s.position_enu_m;
      const double along = v.dot(s.world_from_camera * Eigen::Vector3d::UnitZ());
      const double distance = along > 1e-9 ? along : v.norm();
      const double focus_dioptres = std::isinf(s.focus_distance_m) ? 0.0 : 1.0 / s.focus_distance_m;
      return std::fabs(focus_dioptres - 1.0 / distance);
    };
    team.team.focus_matches.push_back({.at_s = t,
                                       .from_drone = from.name,
                                       .to_drone = to.name,
                                       .subject = subject.name(),
                                       .from_focus_error_dioptres = error(SampleNear(from.plan, t)),
                                       .to_focus_error_dioptres = error(SampleNear(to.plan, t))});
  }
  CheckTeam(team);
  return team;
}

}  // namespace cinepath::shots
