#include "core/team_summary.h"

#include "core/number_format.h"

namespace cinepath {
namespace {

double Duration(const Trajectory& plan) { return plan.samples.empty() ? 0.0 : plan.samples.back().time_s; }

std::string ShotNames(const Trajectory& plan) {
  std::string out;
  for (const auto& shot : plan.shots) out += (out.empty() ? "" : ", ") + shot.name + " (" + shot.type + ")";
  return out;
}

}  // namespace

Json TeamPlanSummaryJson(const TeamPlan& plan) {
  Json drones = Json::array();
  for (const auto& flight : plan.flights) {
    Json shots = Json::array();
    for (const auto& shot : flight.plan.shots) shots.push_back(Json{{"name", shot.name}, {"type", shot.type}});
    Json d{{"name", flight.name},
           {"profile", flight.plan.drone.name},
           {"shots", shots},
           {"samples", flight.plan.samples.size()},
           {"duration_s", RoundToDecimals(Duration(flight.plan), 3)},
           {"feasible", flight.plan.feasibility.feasible()},
           {"violations", flight.plan.feasibility.violations.size()}};
    if (flight.home_enu_m) {
      d["home_enu_m"] =
          Json::array({RoundToDecimals(flight.home_enu_m->x(), 3), RoundToDecimals(flight.home_enu_m->y(), 3),
                       RoundToDecimals(flight.home_enu_m->z(), 3)});
    }
    drones.push_back(d);
  }
  Json edit = Json::array();
  for (const auto& cut : plan.edit) {
    edit.push_back(Json{{"at_s", cut.at_s}, {"drone", cut.drone}, {"match_focus", cut.match_focus}});
  }
  Json conflicts = Json::array();
  for (const auto& c : plan.team.conflicts) {
    conflicts.push_back(Json{{"limit", c.limit},
                             {"drone", c.drone},
                             {"other", c.other},
                             {"start_time_s", RoundToDecimals(c.start_time_s, 3)},
                             {"end_time_s", RoundToDecimals(c.end_time_s, 3)},
                             {"worst_value", RoundToDecimals(c.worst_value, 3)},
                             {"limit_value", RoundToDecimals(c.limit_value, 3)},
                             {"unit", c.unit}});
  }
  if (plan.single) {  // one drone: no edit, no team
    return Json{{"kind", "cinepath plan (one drone)"},
                {"frame_rate_hz", plan.frame_rate_hz},
                {"samples", plan.SampleCount()},
                {"drones", drones}};
  }
  return Json{{"kind", "cinepath plan (several drones)"},
              {"frame_rate_hz", plan.frame_rate_hz},
              {"samples", plan.SampleCount()},
              {"drones", drones},
              {"edit", edit},
              {"team", Json{{"min_separation_m", plan.team.min_separation_m},
                            {"clear", plan.team.clear()},
                            {"conflicts", conflicts},
                            {"focus_matches", plan.team.focus_matches.size()}}}};
}

std::string TeamPlanSummaryText(const TeamPlan& plan) {
  std::string out = "cinepath plan, " + std::to_string(plan.flights.size()) +
                    (plan.flights.size() == 1 ? " drone, " : " drones, ") + std::to_string(plan.SampleCount()) +
                    " samples at " + FormatSignificant(plan.frame_rate_hz, 6) + " Hz\n";
  for (const auto& flight : plan.flights) {
    const auto& v = flight.plan.feasibility.violations;
    out += "  " + flight.name + ": " + flight.plan.drone.name + ", " + std::to_string(flight.plan.samples.size()) +
           " samples (" + FormatFixed(Duration(flight.plan), 2) + " s), shots " + ShotNames(flight.plan) + "; " +
           (v.empty() ? std::string("feasible") : std::to_string(v.size()) + " broken limit(s)");
    if (flight.home_enu_m) {
      out += "; home " + FormatFixed(flight.home_enu_m->x(), 1) + ", " + FormatFixed(flight.home_enu_m->y(), 1) + ", " +
             FormatFixed(flight.home_enu_m->z(), 1) + " m ENU";
    }
    out += "\n";
  }
  if (plan.single) return out;  // one drone: no edit, no team
  if (plan.edit.empty()) {
    out += "edit: none (every camera counts as live)\n";
  } else {
    out += "edit:";
    for (const auto& cut : plan.edit) {
      out += " " + FormatFixed(cut.at_s, 2) + " s " + cut.drone + (cut.match_focus ? " (focus matched)" : "") + ";";
    }
    out.back() = '\n';
  }
  out +=
      "team: min separation " + FormatSignificant(plan.team.min_separation_m, 4) + " m; " +
      (plan.team.clear() ? std::string("no conflicts") : std::to_string(plan.team.conflicts.size()) + " conflict(s)") +
      "\n";
  for (const auto& c : plan.team.conflicts) {
    out += "  " + c.limit + " " + c.drone + "/" + c.other + " t " + FormatFixed(c.start_time_s, 2) + "-" +
           FormatFixed(c.end_time_s, 2) + " s: " + FormatFixed(c.worst_value, 2) + " " + c.unit + " (limit " +
           FormatFixed(c.limit_value, 2) + " " + c.unit + ")\n";
  }
  for (const auto& m : plan.team.focus_matches) {
    out += "  focus matched at " + FormatFixed(m.at_s, 2) + " s " + m.from_drone + " -> " + m.to_drone + " on " +
           m.subject + " (" + FormatFixed(m.from_focus_error_dioptres, 4) + " / " +
           FormatFixed(m.to_focus_error_dioptres, 4) + " dioptres off)\n";
  }
  return out;
}

}  // namespace cinepath
