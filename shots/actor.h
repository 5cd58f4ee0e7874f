// Actors: the named subjects shots frame. Static (one position) or moving along timed keyframes.
//
// An actor's position is its base (feet, wheels, ground contact) in ENU metres; `height_m` is its
// size, used for framing (the aim point is the base raised by half the height). Keyframe times are
// plan time (seconds from the start of the first shot); before the first and after the last key the
// actor holds still.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geodesy.h"
#include "core/ground.h"
#include "core/json.h"
#include "shots/spline.h"

namespace cinepath::shots {

// Where positions in a shot list are resolved: the WGS84 frame for lat/lon, the ground (the scene's
// mesh) for heights given above it. Either may be null.
struct PositionContext {
  PositionContext(const EnuFrame* frame_in = nullptr, const Ground* ground_in = nullptr)  // NOLINT: implicit
      : frame(frame_in), ground(ground_in) {}
  const EnuFrame* frame;
  const Ground* ground;
};

class Actor {
 public:
  Actor(std::string name, double height_m, double heading_deg, PathSpline path);
  // An actor kept on the ground: at every time its base is `above_ground_m` above the highest surface
  // below its path point (ground: non-null, outliving the actor).
  Actor(std::string name, double height_m, double heading_deg, PathSpline path, const Ground* ground,
        double above_ground_m);

  const std::string& name() const { return name_; }
  double height_m() const { return height_m_; }

  Eigen::Vector3d PositionAt(double time_s) const;
  // Where shots place the camera from: PositionAt, but for an actor kept on the ground that moves, the
  // height is the ground's smoothed in time (a C2 spline through the ground height averaged over 0.5 s
  // steps): a camera flies a steady height over the ground's trend instead of copying each kink and
  // bump of a photogrammetry mesh under the actor's feet (those made jerk spikes of thousands of
  // m/s^3). Framing and focus still use PositionAt.
  Eigen::Vector3d CameraBaseAt(double time_s) const;
  Eigen::Vector3d VelocityAt(double time_s) const { return path_.Velocity(time_s); }
  // Where cameras aim: the base raised by half the actor's height.
  Eigen::Vector3d AimPointAt(double time_s) const;
  // Compass heading of travel (degrees) when moving faster than 0.05 m/s horizontally, else the
  // actor's stated facing heading. Outside the keyframe range the heading at the nearest end holds.
  double TravelHeadingDegAt(double time_s) const;

  const PathSpline& path() const { return path_; }

 private:
  std::string name_;
  double height_m_;
  double heading_deg_;
  PathSpline path_;
  const Ground* ground_ = nullptr;  // set: on the ground at every time
  double above_ground_m_ = 0;
  std::optional<PathSpline> smooth_base_up_m_;  // the ground-kept height, smoothed (z of each point)
};

// Parses one element of shots.json "actors" (docs/plan.md): a position or timed keyframes, and
// "on_ground": true to keep the actor on the surface at every sample (needs the scene's mesh). Keyframes
// that all stand at one height above the ground keep the actor at that height between them as well,
// unless "on_ground": false says otherwise.
Actor ParseActor(const JsonField& field, const PositionContext& context);

// Reads a position: [e, n, u] ENU metres under `enu_key`, or {"lat_deg", "lon_deg", and "height_m"
// (WGS84 ellipsoidal) or "amsl_m" (EGM96, core/geoid.h) or "above_ground_m"} under `geo_key` (needs
// the frame). Exactly one must be present. A height above the ground is also written as [e, n] with
// "above_ground_m" beside it in `parent` (default 0): the highest surface at (e, n) plus that (needs
// the ground). InputError names the field.
Eigen::Vector3d ParsePosition(const JsonField& parent, const char* enu_key, const char* geo_key,
                              const PositionContext& context);

}  // namespace cinepath::shots
