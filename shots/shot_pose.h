// Where each shot type puts the camera and what it aims at, at a time inside the shot.
//
// Geometry per type (docs/plan.md has the parameters): positions are relative to the subject's base
// S(t) in ENU; compass bearings b give horizontal unit vectors (sin b, cos b, 0); "up" is +z.
// The shot's easing e(u), u = local time / duration, drives every ramp (sweep angle, distance,
// height, along-track offset); e = u (linear) gives constant rates.
#pragma once

#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "shots/shot_list.h"

namespace cinepath::shots {

struct ShotPose {
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> aim_point_enu_m;       // aim here (screen position, framing)
  std::optional<Eigen::Quaterniond> world_from_camera;  // or a fixed orientation
  std::optional<double> down_up_bearing_deg;            // or straight down, the image top this way
  std::optional<double> tilt_start_deg;                 // CRANE/REVEAL: blend from this pitch ...
  double tilt_weight = 1;                               // ... to the aim by this weight (eased)
  double eased = 0;                                     // e(u), for lens ramps
};

// Compass bearing (degrees) -> horizontal ENU unit vector.
Eigen::Vector3d HorizontalFromBearing(double bearing_deg);

// Evaluates a non-KEYFRAMES shot at local time tau in [0, duration] (clamped). `shot_start_s` is the
// shot's start in plan time (actors move in plan time).
ShotPose EvaluateShotPose(const ShotSpec& shot, const ShotList& list, double shot_start_s, double tau_s);

}  // namespace cinepath::shots
