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
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  ShotPose pose;
  pose.eased = e;
  const Actor* actor = shot.subject >= 0 ? &list.actors[shot.subject] : nullptr;
  if (actor) pose.aim_point_enu_m = actor->AimPointAt(t);

  auto travel = [&](double time_s) {
    return HorizontalFromBearing(shot.travel_bearing_deg ? *shot.travel_bearing_deg
                                                         : actor->TravelHeadingDegAt(time_s));
  };
  auto right_of = [](const Eigen::Vector3d& dir) { return Eigen::Vector3d(dir.y(), -dir.x(), 0.0); };
  // The subject's base the camera is placed from (its up is what height_m is measured from).
  std::optional<double> base_up_m;
  auto base = [&](double time_s) {
    const Eigen::Vector3d p = actor->PositionAt(time_s);
    base_up_m = p.z();
    return p;
  };

  switch (shot.type) {
    case ShotType::kChase: {
      const double tl = t - shot.lag_s;
      const Eigen::Vector3d dir = travel(tl);
      pose.position_enu_m = base(tl) - shot.distance_m * dir + shot.lateral_m * right_of(dir) + shot.height_m * up;
      break;
    }
    case ShotType::kOrbit:
    case ShotType::kHelix: {
      const double bearing = shot.start_bearing_deg + shot.total_angle_deg * e;
      const double r = Lerp(shot.radius_m, shot.radius_end_m, e);
      const double h = Lerp(shot.height_m, shot.height_end_m, e);
      pose.position_enu_m = base(t) + r * HorizontalFromBearing(bearing) + h * up;
      break;
    }
    case ShotType::kFlyby: {
      const Eigen::Vector3d dir = travel(t);
      const double along = shot.speed_m_s * (e * d - shot.closest_at_s);
      pose.position_enu_m = base(t) + shot.side * shot.distance_m * right_of(dir) + along * dir + shot.height_m * up;
      break;
    }
    case ShotType::kDolly: {
      const Eigen::Vector3d dir = travel(t);
      pose.position_enu_m = base(t) + shot.side * shot.distance_m * right_of(dir) +
                            Lerp(shot.along_start_m, shot.along_end_m, e) * dir + shot.height_m * up;
      break;
    }
    case ShotType::kCrane:
    case ShotType::kDronie: {
      pose.position_enu_m = base(t) +
                            Lerp(shot.distance_m, shot.distance_end_m, e) * HorizontalFromBearing(shot.bearing_deg) +
                            Lerp(shot.height_m, shot.height_end_m, e) * up;
      if (shot.tilt_start_deg) {
        pose.tilt_start_deg = shot.tilt_start_deg;
        pose.tilt_weight = e;
      }
      break;
    }
    case ShotType::kTopDown: {
      pose.position_enu_m = base(t) + shot.offset_enu_m + Lerp(shot.height_m, shot.height_end_m, e) * up;
      pose.world_from_camera = LookAt(-up, shot.up_bearing_deg + shot.rotate_deg * e);
      break;
    }
    case ShotType::kDollyZoom: {
      pose.position_enu_m = base(t) +
                            Lerp(shot.distance_m, shot.distance_end_m, e) * HorizontalFromBearing(shot.bearing_deg) +
                            shot.height_m * up;
      break;
    }
    case ShotType::kLockedOff: {
      if (shot.position_enu_m) {
        pose.position_enu_m = *shot.position_enu_m;
      } else {
        pose.position_enu_m =
            base(shot_start_s) + shot.distance_m * HorizontalFromBearing(shot.bearing_deg) + shot.height_m * up;
      }
      if (!actor) {
        GimbalAngles g;
        g.drone_heading_deg = shot.heading_deg;
        g.gimbal_pitch_deg = shot.pitch_deg;
        pose.world_from_camera = WorldFromCameraFromGimbal(g);
      } else if (!shot.pan) {
        pose.aim_point_enu_m = actor->AimPointAt(shot_start_s);  // locked: aimed once
      }
      break;
    }
    case ShotType::kKeyframes: throw InternalError("EvaluateShotPose: KEYFRAMES shots are evaluated by the planner");
  }
  // Heights above the terrain under the camera: the camera keeps its height over the subject's base,
  // taken from the highest surface below it instead.
  if (shot.height_reference == HeightReference::kGround && base_up_m && list.ground) {
    const Eigen::Vector3d& p = pose.position_enu_m;
    const std::optional<double> ground_up_m = list.ground->SurfaceUpM(p.x(), p.y());
    if (!ground_up_m) {
      throw InputError(list.source + ": shot \"" + shot.name + "\": no ground under the camera at t = " +
                       FormatFixed(t, 3) + " s (outside " + list.ground->source() + ")");
    }
    pose.position_enu_m.z() += *ground_up_m - *base_up_m;
  }
  return pose;
}

}  // namespace cinepath::shots
