// The take-off point on the scene's ground (`export --scene` with a mesh). Missions fly heights
// relative to home; a home at the wrong height shifts every waypoint by the error. On a
// photogrammetry scene the ENU origin is wherever the references averaged (on the bundled sample, the
// cameras' mean, 35 m above the beach), so the origin is no take-off point.
//   - Without --home: home is the ground under the plan's first sample, where the drone takes off
//     (the same point plan's altitude limits are measured from).
//   - With --home: its altitude is checked against the mesh's ground there; a difference over the
//     tolerance is reported (and with --strict is exit 3).
#pragma once

#include <optional>

#include "core/geodesy.h"
#include "core/ground.h"
#include "core/trajectory.h"
#include "export/mission_builder.h"

namespace cinepath::exporter {

// Home on the ground under the plan's first sample. `scene_origin` is the mesh's ENU origin; the plan's
// own origin (when it has one) places its samples. InputError when the mesh has no ground there.
HomeSpec TakeoffOnGround(const Trajectory& plan, const Geodetic& scene_origin, const Ground& ground);

struct HomeGroundCheck {
  double ground_amsl_m = 0;  // the mesh's ground under home
  double difference_m = 0;   // home altitude - ground (AMSL, m)
};

// The mesh's ground under `home` and how far home's altitude lies from it; nullopt when the mesh has
// no ground there.
std::optional<HomeGroundCheck> CheckHomeAgainstGround(const HomeSpec& home, const Geodetic& scene_origin,
                                                      const Ground& ground);

}  // namespace cinepath::exporter
