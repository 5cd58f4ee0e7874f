// `cinepath plan`: a shot list -> keyframes, one sample per frame, lens tracks and the feasibility
// report (core/trajectory.h, written as plan.json by core/plan_file.h).
//
// Timing: shots run back to back from t = 0; samples sit at t_k = k / frame_rate for
// k = 0 .. floor(T * frame_rate), T the total duration (so a 10 s plan at 30 fps has 301 samples and
// a zero-length plan one). A sample at a shot boundary belongs to the shot that starts there.
//
// Orientation: the camera aims at the shot's subject (its base raised by half its height) with the
// horizon level, placing it at the lens's screen position (centre by default); vertical views use
// the previous sample's heading for the undefined roll (core/rotation.h). Fixed orientations
// (TOP-DOWN, LOCKED-OFF without a subject, free keyframes with angles) are used as given.
// The drone faces the camera heading (gimbal yaw 0); gimbal pitch/roll come from the orientation.
//
// Transitions: "continuous" (default) starts a shot exactly where, and as fast as, the previous one
// ended: the difference between the shot's own start and the previous end decays to zero over
// blend_s (at most the shot's duration) — position offset with 1 - smootherstep, velocity offset
// with the quintic u - 6u^3 + 8u^4 - 3u^5 (slope 1 at the join, flat at the end), orientation by a
// SLERP of the rotation offset, focal length by a log-ratio offset. Position and velocity are then
// continuous (C1) across the join; acceleration may jump (the feasibility report shows it).
// "cut" jumps, and no rate is checked across it.
//
// Lens: framing (frame_height_fraction) -> focal length by core/optics.h's angle of view at the
// subject distance; fixed/zoom focal lengths interpolate in log space; focus follows the subject
// (distance along the optical axis), racks between subjects in dioptres, or stays at infinity; the
// f-number in stops, the shutter in log time. Values outside the camera's ranges are clamped and
// reported in the feasibility report.
#pragma once

#include <cstddef>
#include <vector>

#include "core/trajectory.h"
#include "shots/shot_list.h"

namespace cinepath::shots {

// Matched focus across a cut (several drones, shots.json "edit"): over [start_s, end_s] the camera
// focuses on `actor` (its aim point, along the optical axis) instead of its shot's own focus, blending
// in before and out after over ramp_s in dioptres (smoothstep) while another camera is live.
struct FocusOverride {
  double start_s = 0;
  double end_s = 0;
  int actor = -1;  // index into ShotList::actors
  double ramp_s = 2.0;
};

struct PlanOptions {
  size_t max_samples = 20'000'000;  // guards against a frame rate x duration that cannot fit
  std::vector<FocusOverride> focus_overrides;
};

Trajectory PlanShots(const ShotList& list, const PlanOptions& options = {});

}  // namespace cinepath::shots
