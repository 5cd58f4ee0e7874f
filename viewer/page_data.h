// What the previs page knows about the plan, as the JSON block the page's code reads (viewer/previs.js):
// the samples' positions and camera orientations in three.js's frame (core/three_frame.h), the lens
// per sample (vertical angle of view by the sensor-fit rule, focus null at infinity), speeds, shots,
// keyframes, subjects and the feasibility report's violations. Numbers are rounded to a fixed number
// of decimals (positions mm, angles 1e-4 deg, quaternions 1e-6), so the page is the same bytes each run.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/geodesy.h"
#include "core/json.h"
#include "core/team_plan.h"
#include "core/trajectory.h"

namespace cinepath::viewer {

// For each sample, whether a cut lies before it: it starts a shot whose transition is "cut" (the drone
// does not fly from the previous sample to it; the page breaks the path there).
std::vector<bool> CutBeforeSamples(const Trajectory& plan);

// Speed along the path at each sample, m/s: central differences, one-sided at the ends and at cuts,
// 0 for a sample alone between two cuts.
std::vector<double> SampleSpeedsMps(const Trajectory& plan);

// The page data of a plan, one drone or several alike (a one-drone plan is a team of one; docs/view.md):
// the detail of `plan.flights[primary]` (its samples with the lens and speed, shots, keyframes, subjects,
// feasibility violations: what the lens graphs, the timeline and the readout show) and a "team" block:
// every flight's name, colour (the palette of `plan --plot`), cuts, home and, for the flights other than
// the primary, samples (time, position, camera orientation, vertical angle of view, focus); the edit; the
// team report's conflicts and minimum separation. `origin`: the WGS84 origin the page shows (the scene's
// or the plan's), none = local metres.
Json PageDataJson(const TeamPlan& plan, size_t primary, const std::string& plan_name,
                  const std::optional<Geodetic>& origin);

}  // namespace cinepath::viewer
