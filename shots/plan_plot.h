// `cinepath plan --plot`: an SVG a crew reads before the numbers. Three panels:
//   * top-down view (east right, north up): each shot's flight in its own colour, subjects' paths in
//     grey with their positions at the frustum times, and the horizontal field of view drawn as a
//     frustum wedge every ~2 s (at least 8 and at most 60 along the plan);
//   * side view (east right, up up) with the same flights and vertical frustums;
//   * lens curves against time: focal length (mm, log scale), focus (dioptres, infinity = 0) and the
//     f-number, with shot boundaries and broken-limit time ranges shaded red.
// Hand-written SVG 1.1 with fixed two-decimal coordinates: deterministic bytes.
#pragma once

#include <string>

#include "core/team_plan.h"
#include "core/trajectory.h"

namespace cinepath::shots {

// One writer for every plan: the flights in one loop. Several drones: every flight in its own colour,
// the edit and the team's conflicts on the time axis. A version 1 plan (one drone): colours by shot.
std::string PlanToSvg(const TeamPlan& plan);
// The plan of one drone, drawn as a version 1 plan.
std::string PlanToSvg(const Trajectory& plan);

}  // namespace cinepath::shots
