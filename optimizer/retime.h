// Retiming: a shot that opted in (`"optimize": {"retime": true}`) and still breaks a limit of motion
// after optimize is flown slower where it needs to be, along the same path, as Roberts & Hanrahan
// (2016) make a shot feasible by changing its progress along the path rather than the path itself.
//
// What time can fix: the limits that are rates of the path or the lens (horizontal speed, climb and
// descent, horizontal acceleration, jerk, yaw rate, gimbal pitch rate, focal length / focus / aperture
// rates). Flown at 1/s of the planned pace, a rate falls by s, an acceleration by s^2, a jerk by s^3.
// A level (altitude, clearance, gimbal range, lens range, distance to an actor) does not change with
// time and is never made worse.
//
// The slow-down s(u) >= 1 is a function of the progress u along the shot (its planned sample index):
// from each broken sample's need, (value / limit)^(1/order), spread to neighbouring samples so that it
// changes by at most kSlopePerSecond a second and smoothed, and 1 at an end the shot shares with a
// continuous neighbour (the pace is continuous across the join). The new clock is
// t(u) = dt * integral of s, rounded up to whole frames; the path is a natural cubic spline through the
// planned samples (C2, so the measured jerk stays smooth), the orientation a slerp, the lens linear in
// the progress. Measured again with `plan`'s own check; where a rate is still broken, the need there
// grows and the warp is made again (a few rounds). The round kept leaves the fewest frames of the plan
// breaking a rate limit (fewer than before), and no level broken by more than before in any shot. A jump
// of pace at a continuous join may leave a neighbour's jerk over its limit for a frame or two; optimize
// runs its ladder again on the retimed plan and keeps it only if the result is never worse than the plan
// as given in any limit of any shot (optimizer.h).
//
// Only shots in which no actor moves are retimed (a moving actor would have to be slowed with the
// camera, which a real take cannot do); the plan's later shots, keyframes and actors move later by
// the time added. A team's drones share one clock, so a team plan is not retimed (team_optimizer.h).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "core/ground.h"
#include "core/trajectory.h"

namespace cinepath::optimizer {

struct RetimedShot {
  std::string shot;
  double duration_before_s = 0;
  double duration_after_s = 0;
  double slowest_factor = 1;         // the largest local slow-down
  std::vector<std::string> limits;   // the rate limits it broke before
  size_t broken_samples_before = 0;  // its samples breaking a rate limit
  size_t broken_samples_after = 0;
};

struct RetimeResult {
  Trajectory plan;                 // the input when nothing was retimed
  std::vector<RetimedShot> shots;  // the shots retimed, in plan order
  std::vector<std::string> notes;  // an opted-in shot not retimed, and why
  double added_s = 0;              // how much longer the plan got
  size_t rate_broken_samples = 0;  // after: the samples of the shots asked that still break a rate limit
};

// Retimes every shot of `plan` whose intent allows it and which breaks a rate limit (with `only`, of those
// the shots it names); `ground` (or null) as the feasibility check takes it. The result's feasibility is
// recomputed.
RetimeResult RetimeShots(const Trajectory& plan, const Ground* ground, const std::set<std::string>* only = nullptr);

// "<limit> in shot \"<shot>\"" for every limit `after` breaks by more than `before` anywhere in that shot
// (shots matched by name, so a plan and its retimed self compare); empty when it is never worse.
std::vector<std::string> WorseThan(const Trajectory& before, const Trajectory& after, const Ground* ground);

// The limits RetimeShots can fix, with the power of time in each: 1 for a rate, 2 for an acceleration,
// 3 for a jerk; 0 for a limit time does not change.
int TimeOrderOfLimit(const std::string& limit);

}  // namespace cinepath::optimizer
