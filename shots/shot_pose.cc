#include "shots/shot_pose.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/error.h"
#include "core/number_format.h"
#include "core/rotation.h"

namespace cinepath::shots {
namespace {

double Lerp(double a, double b, double w) { return a + (b - a) * w; }

// The subject's frame a shot places its camera in.
struct SubjectFrame {
  const ShotSpec& shot;
  const Actor* actor;
  std::optional<double> base_up_m;  // the up of the last base asked for (what height_m is measured from)

  // The direction of travel at a time: the shot's bearing, or the subject's heading.
  Eigen::Vector3d Travel(double time_s) const {
    return HorizontalFromBearing(shot.travel_bearing_deg ? *shot.travel_bearing_deg
                                                         : actor->CameraTravelHeadingDegAt(time_s));
  }
  // The subject's base the camera is placed from (its path smoothed in time, Actor::CameraBaseAt).
  Eigen::Vector3d Base(double time_s) {
    const Eigen::Vector3d p = actor->CameraBaseAt(time_s);
    base_up_m = p.z();
    return p;
  }
};

Eigen::Vector3d RightOf(const Eigen::Vector3d& dir) { return Eigen::Vector3d(dir.y(), -dir.x(), 0.0); }

// Where each shot type puts the camera at eased progress e (time t, duration d), and for some types its
// orientation or tilt.
void PlaceCamera(const ShotSpec& shot, double shot_start_s, double t, double e, double d, SubjectFrame& f,
                 ShotPose& pose) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  switch (shot.type) {
    case ShotType::kChase: {
      const double tl = t - shot.lag_s;
      const Eigen::Vector3d dir = f.Travel(tl);
      pose.position_enu_m = f.Base(tl) - shot.distance_m * dir + shot.lateral_m * RightOf(dir) + shot.height_m * up;
      break;
    }
    case ShotType::kOrbit:
    case ShotType::kHelix: {
      const double bearing = shot.start_bearing_deg + shot.total_angle_deg * e;
      const double r = Lerp(shot.radius_m, shot.radius_end_m, e);
      const double h = Lerp(shot.height_m, shot.height_end_m, e);
      pose.position_enu_m = f.Base(t) + r * HorizontalFromBearing(bearing) + h * up;
      break;
    }
    case ShotType::kFlyby: {
      const Eigen::Vector3d dir = f.Travel(t);
      const double along = shot.speed_m_s * (e * d - shot.closest_at_s);
      pose.position_enu_m = f.Base(t) + shot.side * shot.distance_m * RightOf(dir) + along * dir + shot.height_m * up;
      break;
    }
    case ShotType::kDolly: {
      const Eigen::Vector3d dir = f.Travel(t);
      pose.position_enu_m = f.Base(t) + shot.side * shot.distance_m * RightOf(dir) +
                            Lerp(shot.along_start_m, shot.along_end_m, e) * dir + shot.height_m * up;
      break;
    }
    case ShotType::kCrane:
    case ShotType::kDronie: {
      pose.position_enu_m = f.Base(t) +
                            Lerp(shot.distance_m, shot.distance_end_m, e) * HorizontalFromBearing(shot.bearing_deg) +
                            Lerp(shot.height_m, shot.height_end_m, e) * up;
      if (shot.tilt_start_deg) {
        pose.tilt_start_deg = shot.tilt_start_deg;
        pose.tilt_weight = e;
      }
      break;
    }
    case ShotType::kTopDown: {
      pose.position_enu_m = f.Base(t) + shot.offset_enu_m + Lerp(shot.height_m, shot.height_end_m, e) * up;
      pose.down_up_bearing_deg = shot.up_bearing_deg + shot.rotate_deg * e;  // the planner levels it
      break;
    }
    case ShotType::kDollyZoom: {
      pose.position_enu_m = f.Base(t) +
                            Lerp(shot.distance_m, shot.distance_end_m, e) * HorizontalFromBearing(shot.bearing_deg) +
                            shot.height_m * up;
      break;
    }
    case ShotType::kLockedOff: {
      if (shot.position_enu_m) {
        pose.position_enu_m = *shot.position_enu_m;
      } else {
        pose.position_enu_m =
            f.Base(shot_start_s) + shot.distance_m * HorizontalFromBearing(shot.bearing_deg) + shot.height_m * up;
      }
      if (!f.actor) {
        pose.world_from_camera = shot.locked_world_from_camera;
      } else if (!shot.pan) {
        pose.aim_point_enu_m = f.actor->AimPointAt(shot_start_s);  // locked: aimed once
      }
      break;
    }
    case ShotType::kKeyframes: throw InternalError("EvaluateShotPose: KEYFRAMES shots are evaluated by the planner");
  }
}

// Heights above the terrain under the camera: the camera keeps its height over the subject's base,
// taken from the highest surface below it instead.
void KeepHeightOverGround(const ShotSpec& shot, const ShotList& list, double t, const std::optional<double>& base_up_m,
                          ShotPose& pose) {
  if (shot.height_reference != HeightReference::kGround || !base_up_m || !list.ground) return;
  const Eigen::Vector3d& p = pose.position_enu_m;
  const std::optional<double> ground_up_m = list.ground->SurfaceUpM(p.x(), p.y());
  if (!ground_up_m) {
    throw InputError(list.source + ": shot \"" + shot.name + "\": no ground under the camera at t = " +
                     FormatFixed(t, 3) + " s (outside " + list.ground->source() + ")");
  }
  pose.position_enu_m.z() += *ground_up_m - *base_up_m;
}

}  // namespace

Eigen::Vector3d HorizontalFromBearing(double bearing_deg) {
  const double b = RadFromDeg(bearing_deg);
  return {std::sin(b), std::cos(b), 0.0};
}

ShotPose EvaluateShotPose(const ShotSpec& shot, const ShotList& list, double shot_start_s, double tau_s) {
  const double d = shot.duration_s;
  const double tau = std::clamp(tau_s, 0.0, d);
  const double u = d > 0 ? tau / d : 0.0;
  const double e = Ease(shot.easing, u);
  const double t = shot_start_s + tau;
  ShotPose pose;
  pose.eased = e;
  const Actor* actor = shot.subject >= 0 ? &list.actors[shot.subject] : nullptr;
  if (actor) pose.aim_point_enu_m = actor->AimPointAt(t);
  SubjectFrame frame{shot, actor, std::nullopt};
  PlaceCamera(shot, shot_start_s, t, e, d, frame, pose);
  KeepHeightOverGround(shot, list, t, frame.base_up_m, pose);
  return pose;
}

}  // namespace cinepath::shots
