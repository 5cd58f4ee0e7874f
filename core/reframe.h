// A plan moved from the ENU frame of its own origin into the ENU frame of another origin (a scene's):
// positions through ECEF, directions and orientations by the rotation between the two tangent frames.
// Exact (GeographicLib), so a plan made about one origin lands on a mesh made about another, metres
// or kilometres away, without the error of shifting by the difference of two flat frames.
#pragma once

#include <Eigen/Geometry>

#include "core/geodesy.h"
#include "core/team_plan.h"
#include "core/trajectory.h"

namespace cinepath {

// The plan in the frame of `origin`: samples, keyframes and subjects; `plan.origin` becomes `origin`.
// A plan without an origin is taken to be in that frame already and is returned unchanged.
Trajectory ReframeToOrigin(Trajectory plan, const Geodetic& origin);
// Every flight and take-off point of a team.
TeamPlan ReframeToOrigin(TeamPlan plan, const Geodetic& origin);

// The rigid motion that takes ENU coordinates about `from` to ENU coordinates about `to`: the rotation
// between the two tangent frames and the translation of `from` seen from `to` (through ECEF). Both
// frames are Cartesian, so the motion is exact for any point; `plan` moves a scene's mesh with it into
// the frame of a shot list made about another origin.
Eigen::Isometry3d EnuFromEnu(const Geodetic& to, const Geodetic& from);

}  // namespace cinepath
