// A plan for several drones on one clock (plan.json "cinepath.plan/2"): one flight per drone, the cut
// the crew intends (`edit`), and the team report (separation, drones in each other's shots, focus
// matched across cuts). docs/plan-format.md, "Several drones".
//
// Every flight samples the same clock: sample k of every drone is at t = k / frame_rate_hz. A flight
// that ends before another holds its last position (hovering) for the team checks.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/error.h"
#include "core/geodesy.h"
#include "core/json.h"
#include "core/trajectory.h"

namespace cinepath {

struct DroneFlight {
  std::string name;                           // the drone's name in shots.json
  std::optional<Eigen::Vector3d> home_enu_m;  // its take-off point, when the shot list gives one
  Trajectory plan;                            // its samples, keyframes, lens, camera, profile, feasibility
};

// From `at_s` on, `drone`'s camera is live (until the next cut). `match_focus`: at this cut the incoming
// camera focuses on the subject the outgoing camera had in focus, so the cut keeps that subject sharp.
struct EditCut {
  double at_s = 0;
  std::string drone;
  bool match_focus = false;
};

// One team limit broken over a time range (consecutive samples merged).
struct TeamConflict {
  std::string limit;  // "separation" | "in_shot"
  std::string drone;  // separation: the first of the pair; in_shot: the drone whose camera sees the other
  std::string other;  // the second drone / the drone seen
  double start_time_s = 0;
  double end_time_s = 0;
  double worst_value = 0;  // separation: least distance (m); in_shot: largest projected diameter (px)
  double limit_value = 0;  // separation: min_separation_m; in_shot: the visibility threshold (px)
  std::string unit;        // "m" | "px"
};

// What a matched-focus cut gives: the subject, and its distance from each camera's focus in dioptres.
struct FocusMatch {
  double at_s = 0;
  std::string from_drone, to_drone, subject;
  double from_focus_error_dioptres = 0;  // |1/focus - 1/subject distance| of the outgoing camera at the cut
  double to_focus_error_dioptres = 0;    // the same for the incoming camera
};

struct TeamReport {
  double min_separation_m = 0;  // the largest of the drones' profiles' (every pair keeps it)
  std::vector<TeamConflict> conflicts;
  std::vector<FocusMatch> focus_matches;
  bool clear() const { return conflicts.empty(); }
};

struct TeamPlan {
  std::optional<Geodetic> origin;
  double frame_rate_hz = 30;
  std::vector<DroneFlight> flights;
  std::vector<EditCut> edit;
  TeamReport team;
  // A plan read from a "cinepath.plan/1" file (one drone, no names): written back in that version.
  bool single = false;
  // Written by `cinepath optimize` for the team terms; null otherwise.
  Json optimized;

  // The index of the flight named `name`, or -1.
  int FindFlight(const std::string& name) const {
    for (size_t i = 0; i < flights.size(); ++i) {
      if (flights[i].name == name) return static_cast<int>(i);
    }
    return -1;
  }
  // The number of samples on the shared clock (the longest flight's).
  size_t SampleCount() const {
    size_t n = 0;
    for (const auto& f : flights) n = std::max(n, f.plan.samples.size());
    return n;
  }
};

// The live drone's flight index at time t (the last cut at or before t), or -1 before the first cut or
// without an edit.
inline int LiveFlightAt(const TeamPlan& plan, double t) {
  int live = -1;
  for (const auto& cut : plan.edit) {
    if (cut.at_s <= t + 1e-9) live = plan.FindFlight(cut.drone);
  }
  return live;
}

// Outputs for several drones go to a folder per drone (export, render): a drone's name must be usable as
// a folder name (as shots.json requires: not empty, no '/' or '\\', not "." or ".."), and `reserved`
// names (render's "edit") are refused. InputError naming `source` and the drone.
inline void CheckDroneFolderName(const std::string& name, const std::string& source,
                                 const std::vector<std::string>& reserved = {}) {
  if (name.empty() || name.find_first_of("/\\") != std::string::npos || name == "." || name == "..") {
    throw InputError(source + ": drone \"" + name +
                     "\": its outputs go to a folder of that name (no '/', '\\', \".\" or \"..\")");
  }
  for (const auto& r : reserved) {
    if (name == r) throw InputError(source + ": drone \"" + name + "\": the folder \"" + r + "\" is reserved here");
  }
}

}  // namespace cinepath
