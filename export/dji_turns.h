// The path a DJI aircraft flies through WPML waypoints with waypointTurnMode coordinateTurn, and the
// choice of each waypoint's waypointTurnDampingDist so that path stays within --max-deviation-m.
//
// Why this turn mode: toPointAndPassWithContinuityCurvature flies a curve whose shape DJI does not
// document, so its deviation cannot be bounded. With coordinateTurn the aircraft leaves the incoming
// leg a damping distance d before the waypoint and joins the outgoing leg d after it, cutting the
// corner without passing through the waypoint (docs/mission-formats.md §4.1: d in (0, segment length], and the two
// damping distances on a segment sum to less than its length). Where no d keeps the path within the
// tolerance (or the aircraft must stop: first/last waypoint, hover, cut), the waypoint uses
// toPointAndStopWithDiscontinuityCurvature: straight in, stop, straight out.
//
// Model of the corner (d > 0): the circular arc tangent to both legs at A = P − d·u_in and
// B = P + d·u_out (u = unit leg directions, in the plane of the two legs). With turn angle δ between
// u_in and u_out the radius is r = d / tan(δ/2) and the arc passes d·tan(δ/4) from the waypoint P
// (90° corner, d = 2 m → 0.8284 m). The flown path = straight pieces between the arcs' ends plus
// the arcs; the deviation of a plan sample is its distance to that path (the arcs are evaluated as
// 32-chord polylines, error < 3e-4·d). DJI's exact curve inside the corner is not published; this
// arc is the model, documented in docs/export.md.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/trajectory.h"

namespace cinepath::exporter {

constexpr double kDjiMinDampingM = 0.2;  // smallest damping distance tried (assumed; docs/export.md)

struct TurnFit {
  std::vector<double> damping_m;  // per waypoint; 0 = stop at the waypoint (no turn)
  double max_deviation_m = 0;     // of the modelled flown path, over all samples
};

// `waypoints`: selected sample indices (increasing, first = 0, last = samples.size() − 1);
// `must_stop[w]`: the aircraft stops at waypoint w (first and last always do).
TurnFit FitCoordinatedTurns(const std::vector<TrajectorySample>& samples, const std::vector<int>& waypoints,
                            const std::vector<bool>& must_stop, double max_deviation_m);

// Distance from `q` to the modelled path through `corners` with damping distances `damping_m`
// (same length; 0 = sharp corner), restricted to the part between corners[w] and corners[w + 1]
// including the full turns at both ends.
double DistanceToTurnPath(const std::vector<Eigen::Vector3d>& corners, const std::vector<double>& damping_m, size_t w,
                          const Eigen::Vector3d& q);

// Largest deviation of samples [waypoints[w], waypoints[w+1]] (for every w) from the modelled path.
double TurnPathDeviation(const std::vector<TrajectorySample>& samples, const std::vector<int>& waypoints,
                         const std::vector<double>& damping_m);

}  // namespace cinepath::exporter
