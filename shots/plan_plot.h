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

std::string PlanToSvg(const Trajectory& plan);
// Several drones: every flight in its own colour, the team's conflicts shaded on the time axis. A version
// 1 plan gives PlanToSvg's picture.
std::string TeamPlanToSvg(const TeamPlan& plan);

}  // namespace cinepath::shots
