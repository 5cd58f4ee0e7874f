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
  // Where shots place the camera from: for an actor that moves on a linear or Catmull-Rom path, or is kept on the
  // ground, its position smoothed in time (a C2 spline through the position averaged over half-second steps,
  // SmoothForCameras); else PositionAt. A camera placed rigidly from the keyed path copied each of its kinks: a
  // Catmull-Rom path is only C1 at its keys (an acceleration step), a linear one C0, and a ground-kept height copies
  // every bump of a photogrammetry mesh (jerk spikes of hundreds to thousands of m/s^3). Framing and focus still use
  // PositionAt.
  Eigen::Vector3d CameraBaseAt(double time_s) const;
  Eigen::Vector3d VelocityAt(double time_s) const { return path_.Velocity(time_s); }
  // Where cameras aim: the base raised by half the actor's height.
  Eigen::Vector3d AimPointAt(double time_s) const;
  // Compass heading of travel (degrees) when moving faster than kMovingMS horizontally, else the
  // actor's stated facing heading. Outside the keyframe range the heading at the nearest end holds.
  double TravelHeadingDegAt(double time_s) const;
  // The heading shots place the camera by (CHASE behind, FLYBY and DOLLY beside): the direction of the velocity
  // averaged as CameraBaseAt's position, through a C2 spline, blending into the facing heading at rest. The
  // heading of a C1 path turns at a rate that steps at each key; a camera metres to the side of it stepped in
  // velocity there.
  double CameraTravelHeadingDegAt(double time_s) const;
  static constexpr double kMovingMS = 0.05;  // slower than this, an actor faces its stated heading
  // For a shot that follows the actor past its last key, where it stops (PlanShots): the camera's base eases
  // into the stop over the second on either side of the key, as the averages see the actor standing still
  // after it, instead of running on at the key's velocity and stopping dead with it; the direction of travel
  // holds its last.
  void EaseCameraIntoTheStop();
  // The speed (m/s) at which the actor arrives at its last key, where it stops (0 with one key).
  double SpeedAtLastKeyMS() const;

  const PathSpline& path() const { return path_; }
  bool kept_on_ground() const { return ground_ != nullptr; }

  // The keys whose height the shot list gave as an absolute up value ([e, n, u], or lat/lon with a
  // height), not above the ground: their index in path() and where the field that gave them is (file: path).
  struct AbsoluteHeightKey {
    size_t key;
    std::string field;
  };
  const std::vector<AbsoluteHeightKey>& absolute_height_keys() const { return absolute_height_keys_; }
  void SetAbsoluteHeightKeys(std::vector<AbsoluteHeightKey> keys) { absolute_height_keys_ = std::move(keys); }

 private:
  std::string name_;
  double height_m_;
  double heading_deg_;
  PathSpline path_;
  const Ground* ground_ = nullptr;  // set: on the ground at every time
  double above_ground_m_ = 0;
  void SmoothForCameras();
  bool ease_into_stop_ = false;              // EaseCameraIntoTheStop
  std::optional<PathSpline> camera_base_;    // CameraBaseAt's positions
  std::optional<PathSpline> camera_travel_;  // CameraTravelHeadingDegAt's unit directions (z = 0)
  std::vector<AbsoluteHeightKey> absolute_height_keys_;
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
