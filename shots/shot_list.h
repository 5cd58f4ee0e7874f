// The shot list (shots.json, "schema": "cinepath.shots/1"): what a crew wants to film.
// Reference: docs/plan.md and docs/shots.schema.json. Parsing checks every field and names the JSON
// path in its errors ("shots.json: shots[2].radius_m: must be > 0").
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/easing.h"
#include "core/geodesy.h"
#include "core/json.h"
#include "core/team_plan.h"
#include "core/trajectory.h"
#include "shots/actor.h"
#include "shots/lens_track.h"
#include "shots/shot_type.h"
#include "shots/spline.h"

namespace cinepath::shots {

inline constexpr const char* kShotsSchema = "cinepath.shots/1";

struct RackFocus {
  double at_s = 0;          // shot-local start of the rack
  double duration_s = 1.0;  // rack length (dioptre blend with smoothstep)
  int actor = -1;           // index into ShotList::actors
};

struct LensSpec {
  std::optional<double> focal_length_mm;
  std::optional<double> focal_length_end_mm;
  std::optional<double> frame_height_fraction;  // framing: subject height / frame height
  std::optional<double> frame_height_fraction_end;
  Eigen::Vector2d screen_position{0.5, 0.5};  // where the subject sits: x right, y down, [0, 1]
  enum class Focus { kFollow, kInfinity, kFixed } focus = Focus::kFollow;
  double focus_distance_m = 10;  // kFixed
  std::vector<RackFocus> rack;
  std::vector<ScalarKey> f_number;  // shot-local keys (one key = constant)
  std::vector<ScalarKey> shutter_s;
  // Depth-of-field goals for `optimize` (the planner carries them into plan.json's shot intent).
  std::vector<int> sharp;                       // actors that must lie inside the depth of field
  std::optional<double> background_blur_px;     // least blur-circle diameter behind the subject
  std::optional<double> background_distance_m;  // where the background is, without a mesh
};

// The shot-level "optimize" block: what `optimize` may not move, and how far it may move the rest.
struct OptimizeSpec {
  std::vector<std::string> hold;  // out of kOptimizeChannels (core/trajectory.h)
  std::optional<double> max_deviation_m;
  bool retime = false;  // optimize may slow the shot down (no moving actor in it)
};

// One free keyframe of a KEYFRAMES shot (shot-local time).
struct CameraKey {
  double time_s = 0;
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  std::optional<Eigen::Quaterniond> world_from_camera;  // from angles or a look-at at the key time
  std::optional<double> focal_length_mm;
  std::optional<double> focus_distance_m;  // +inf allowed
  std::optional<double> f_number;
  Easing easing = Easing::kLinear;  // easing of the segment that starts at this key
};

enum class OrientationInterpolation { kSlerp, kSquad };

// What a shot's height_m is measured from: the subject's base (the default) or the terrain under the
// camera (the scene's mesh).
enum class HeightReference { kSubject, kGround };

struct ShotSpec {
  std::string name;
  int drone = -1;  // index into ShotList::drones; -1 in a one-drone list
  ShotType type = ShotType::kOrbit;
  std::string type_name;  // as written (e.g. "TRACK")
  int subject = -1;       // index into ShotList::actors, -1 = none
  double duration_s = 0;
  Easing easing = Easing::kLinear;
  bool cut = false;      // transition from the previous shot: explicit cut (else continuous)
  double blend_s = 2.0;  // continuous transition: the offset decays over this time (<= duration)
  HeightReference height_reference = HeightReference::kSubject;
  LensSpec lens;
  OptimizeSpec optimize;

  // Geometry (metres, degrees; which apply depends on the type, see docs/plan.md).
  double distance_m = 0, distance_end_m = 0;
  double height_m = 0, height_end_m = 0;
  double radius_m = 0, radius_end_m = 0;
  double lateral_m = 0;
  double lag_s = 0;
  double total_angle_deg = 0;    // ORBIT/HELIX sweep (signed: + clockwise seen from above)
  double start_bearing_deg = 0;  // compass bearing from the subject to the camera
  double bearing_deg = 0;
  std::optional<double> travel_bearing_deg;
  double side = 1;  // +1 right of the direction of travel, -1 left
  double speed_m_s = 0;
  double closest_at_s = 0;
  double along_start_m = 0, along_end_m = 0;
  std::optional<double> tilt_start_deg;  // CRANE/REVEAL: gimbal pitch at the start
  double up_bearing_deg = 0;             // TOP-DOWN: compass direction of the image top
  double rotate_deg = 0;                 // TOP-DOWN: rotation over the shot (clockwise)
  Eigen::Vector3d offset_enu_m = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> position_enu_m;  // LOCKED-OFF
  // LOCKED-OFF without a subject: its heading_deg and pitch_deg, taken against true north and the local
  // vertical at its position (core/local_level.h).
  Eigen::Quaterniond locked_world_from_camera = Eigen::Quaterniond::Identity();
  bool pan = false;  // LOCKED-OFF: pan to hold the subject

  // KEYFRAMES
  std::vector<CameraKey> keys;
  PathInterpolation interpolation = PathInterpolation::kCatmullRom;
  OrientationInterpolation orientation = OrientationInterpolation::kSquad;
};

// One drone of a team (shots.json "drones"): its name, aircraft, camera and take-off point.
struct DroneSpec {
  std::string name;
  DroneProfile drone;
  CameraSpec camera;
  std::optional<Eigen::Vector3d> home_enu_m;
};

struct ShotList {
  std::string source;  // file name, for messages
  std::optional<Geodetic> origin;
  double frame_rate_hz = 30;
  CameraSpec camera;
  DroneProfile drone;
  std::vector<Actor> actors;
  std::vector<ShotSpec> shots;
  std::shared_ptr<const Ground> ground;  // the scene's mesh (plan --scene), or null
  // Several drones (empty: one drone, `camera` and `drone` above). Each shot names its drone; the shots
  // of one drone run back to back, the drones in parallel on one clock.
  std::vector<DroneSpec> drones;
  std::vector<EditCut> edit;  // which camera is live when (shots.json "edit"; several drones only)

  int FindActor(const std::string& name) const;  // -1 when absent
  int FindDrone(const std::string& name) const;  // -1 when absent
};

// The shot list's own "origin" (nullopt without one), read before the list itself so that a scene's mesh
// can be moved into its frame (`plan --scene`). InputError naming the field when it is malformed.
std::optional<Geodetic> ShotListOrigin(const Json& document, const std::string& source);
// Two origins are one when they agree within 1e-9 deg and 1e-6 m (a JSON round trip of the same origin).
bool SameOrigin(const Geodetic& a, const Geodetic& b);

// Parses a shot list. `scene_origin` (from the scene's scene.json) is used when shots.json has no
// "origin"; when both are present they must be the SameOrigin, since `ground` answers in that one frame
// (cinepath plan passes the list's own origin, its ground moved into that frame, when they differ).
// `ground` (the scene's mesh) resolves heights above the ground, actors kept on it, and shots whose heights
// are measured from it; without it those are an InputError naming the key.
ShotList ParseShotList(const Json& document, const std::string& source,
                       const std::optional<Geodetic>& scene_origin = std::nullopt,
                       std::shared_ptr<const Ground> ground = nullptr);
ShotList ReadShotListFile(const std::filesystem::path& path, const std::optional<Geodetic>& scene_origin = std::nullopt,
                          std::shared_ptr<const Ground> ground = nullptr);

}  // namespace cinepath::shots
