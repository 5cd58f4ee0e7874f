// The sampled camera flight every stage after `plan` exchanges (plan.json in memory).
//
// Frames and units (docs/design.md): positions in the scene's local ENU frame (metres) about `origin`;
// world_from_camera maps camera-frame vectors (x right, y down, z forward) into ENU; quaternions are
// Hamilton (w, x, y, z), unit norm. Drone yaw is a compass heading (clockwise from true north,
// degrees, [0, 360)); gimbal angles are relative to the horizon and the drone's heading:
// pitch 0 = level, -90 = straight down; gimbal yaw relative to the drone's nose.
// Focus at infinity is +infinity in memory and null in JSON.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/drone_profile.h"
#include "core/geodesy.h"
#include "core/json.h"
#include "core/optics.h"

namespace cinepath {

struct CameraSpec {
  std::string filmback = "custom";  // preset name, or "custom"
  double sensor_width_mm = 24.89;   // Super 35 by default
  double sensor_height_mm = 18.67;
  int width_px = 3840;
  int height_px = 2160;
  double min_focal_length_mm = 24;
  double max_focal_length_mm = 24;
  double min_f_number = 2.8;
  double max_f_number = 16;
  double min_focus_distance_m = 0.5;
  double coc_mm = 0.0;  // acceptable blur for DoF reports; 0 = derive from the filmback diagonal
  // Lens servo limits for feasibility checks (planning priors, docs/optics.md).
  double max_focal_rate_mm_s = 20;       // zoom speed
  double max_focus_rate_m_s = 15;        // follow-focus speed
  double max_aperture_rate_stops_s = 3;  // iris speed

  // The part of the sensor the image covers (core/optics.h, sensor fit): the full width, and
  // width * height_px / width_px of the height. Framing and angles of view use this, not the filmback.
  ImageExtentMm image_extent_mm() const { return ImageExtentOnSensorMm(sensor_width_mm, width_px, height_px); }
};

struct TrajectorySample {
  double time_s = 0;
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  Geodetic geodetic;  // filled when the plan has an origin
  Eigen::Quaterniond world_from_camera = Eigen::Quaterniond::Identity();
  double drone_heading_deg = 0;  // compass heading of the drone's nose
  double gimbal_pitch_deg = 0;   // -90 straight down .. +30 up
  double gimbal_roll_deg = 0;
  double gimbal_yaw_deg = 0;  // relative to the drone's nose
  double focal_length_mm = 24;
  double focus_distance_m = 10;  // +inf = focused at infinity
  double f_number = 2.8;
  double shutter_s = 1.0 / 50.0;
  std::string shot;  // name of the shot this sample belongs to
  std::vector<std::string> subjects_in_frame;
};

// What a shot asks of the picture beyond its samples: the targets `optimize` keeps to (docs/plan.md,
// "lens" and "optimize"). Absent keys keep their defaults and are not written.
// A rack focus of a shot's intent: from `at_s` (shot-local) the focus blends in dioptres (smoothstep)
// over `duration_s` to `subject`.
struct RackIntent {
  double at_s = 0;
  double duration_s = 1;
  std::string subject;
};

// How a shot sets its focus (plan.json "focus"): the subject's distance along the optical axis, a
// fixed distance, infinity, free keyframes, or the subject's distance with racks to other actors.
// "" in a plan written before the key existed.
inline const std::vector<std::string> kFocusModes = {"follow", "fixed", "infinity", "keys", "rack"};

struct ShotIntent {
  std::string focus;                                // out of kFocusModes, or "" (not recorded)
  std::vector<RackIntent> rack;                     // focus == "rack": in time order
  std::optional<double> frame_height_fraction;      // subject height / frame height, at the start
  std::optional<double> frame_height_fraction_end;  // at the end (log-interpolated), when it changes
  Eigen::Vector2d screen_position{0.5, 0.5};        // where the subject's aim point sits: x right, y down
  std::vector<std::string> sharp;                   // actors that must lie inside the depth of field
  std::optional<double> background_blur_px;         // least blur-circle diameter behind the subject
  std::optional<double> background_distance_m;      // the background behind the subject, without a mesh
  std::vector<std::string> hold;                    // what optimize may not move (kOptimizeChannels)
  std::optional<double> max_deviation_m;            // from the planned path (optimize's default: 5 m)
  bool retime = false;  // optimize may slow the shot down where its limits need more time (optimizer/retime.h)

  bool empty() const {
    return focus.empty() && rack.empty() && !frame_height_fraction && !frame_height_fraction_end &&
           screen_position == Eigen::Vector2d(0.5, 0.5) && sharp.empty() && !background_blur_px &&
           !background_distance_m && hold.empty() && !max_deviation_m && !retime;
  }
};
// The names `hold` accepts.
inline const std::vector<std::string> kOptimizeChannels = {"position", "orientation", "focal_length", "focus",
                                                           "aperture"};

struct ShotSpan {
  std::string name;
  std::string type;  // "ORBIT", "CHASE", ...
  double start_time_s = 0;
  double end_time_s = 0;
  std::string subject;                    // the actor the shot frames ("" for none)
  std::string transition = "continuous";  // how this shot joins the previous one: "continuous" | "cut"
  ShotIntent intent;
};

// A key pose a shot was built from: what an editor shows as keyframes (the samples are the truth).
struct Keyframe {
  std::string shot;
  double time_s = 0;
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond world_from_camera = Eigen::Quaterniond::Identity();
  double focal_length_mm = 24;
  double focus_distance_m = 10;  // +inf = infinity
  double f_number = 2.8;
};

// A subject's path, one position per sample (aligned with Trajectory::samples). The position is the
// subject's base (its feet / ground contact); height_m its size for framing.
struct SubjectTrack {
  std::string name;
  double height_m = 1.8;
  std::vector<Eigen::Vector3d> positions_enu_m;
};

// One broken limit over a time range (consecutive samples merged).
struct FeasibilityViolation {
  std::string limit;  // "horizontal_speed", "acceleration", "jerk", "yaw_rate", "gimbal_pitch", ...
  std::string shot;
  double start_time_s = 0;
  double end_time_s = 0;
  double worst_value = 0;  // the worst value seen in the range, in `unit`
  double limit_value = 0;
  std::string unit;
};

struct FeasibilityReport {
  std::vector<FeasibilityViolation> violations;
  // Checks that could not run, each with why ("terrain_clearance: no scene mesh"), so that a feasible
  // report says what it did not check.
  std::vector<std::string> skipped;
  bool feasible() const { return violations.empty(); }
};

struct Trajectory {
  std::optional<Geodetic> origin;  // WGS84 origin of the ENU frame, when known
  double frame_rate_hz = 30;
  CameraSpec camera;
  std::vector<ShotSpan> shots;
  std::vector<TrajectorySample> samples;  // one per frame, increasing time
  // Added by `cinepath plan` (core/plan_file.h); empty for trajectories built elsewhere.
  DroneProfile drone;  // the aircraft the plan is checked against (core/drone_profiles.h)
  std::vector<Keyframe> keyframes;
  std::vector<SubjectTrack> subjects;
  FeasibilityReport feasibility;
  // Written by `cinepath optimize`: how the plan was optimized ({quality, scene, terms, ...}); null for a
  // plan straight from `plan`.
  Json optimized;
  // What the reader filled in that the file did not give (a drone field taken from the named profile),
  // one "<file>: <path>: ..." line each, for the command to print as a warning. Never written.
  std::vector<std::string> notes;
};

}  // namespace cinepath
