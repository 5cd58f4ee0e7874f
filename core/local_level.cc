#include "core/local_level.h"

namespace cinepath {

GimbalAngles LocalGimbalAngles(const EnuFrame* frame, const Eigen::Vector3d& position_enu_m,
                               const Eigen::Quaterniond& world_from_camera, double drone_heading_deg) {
  if (!frame) return GimbalFromWorldFromCamera(world_from_camera, drone_heading_deg);
  const Eigen::Quaterniond local_from_enu(frame->LocalLevelFromEnu(position_enu_m));
  return GimbalFromWorldFromCamera(local_from_enu * world_from_camera.normalized(), drone_heading_deg);
}

Eigen::Quaterniond LocalWorldFromCamera(const EnuFrame* frame, const Eigen::Vector3d& position_enu_m,
                                        const GimbalAngles& angles) {
  const Eigen::Quaterniond local_from_camera = WorldFromCameraFromGimbal(angles);
  if (!frame) return local_from_camera;
  const Eigen::Quaterniond enu_from_local(frame->LocalLevelFromEnu(position_enu_m).transpose());
  Eigen::Quaterniond q = (enu_from_local * local_from_camera).normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // the same rotation, w >= 0 as everywhere
  return q;
}

Eigen::Quaterniond LocalLookAt(const EnuFrame* frame, const Eigen::Vector3d& position_enu_m,
                               const Eigen::Vector3d& forward_enu, double fallback_heading_deg) {
  if (!frame) return LookAt(forward_enu, fallback_heading_deg);
  const Eigen::Matrix3d local_from_enu = frame->LocalLevelFromEnu(position_enu_m);
  Eigen::Quaterniond q =
      (Eigen::Quaterniond(local_from_enu.transpose()) * LookAt(local_from_enu * forward_enu, fallback_heading_deg))
          .normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return q;
}

void SetLocalAngles(const EnuFrame* frame, TrajectorySample& sample, double drone_heading_deg) {
  const Eigen::Quaterniond q = sample.world_from_camera.normalized();
  const GimbalAngles g =
      frame ? GimbalFromWorldFromCamera(
                  Eigen::Quaterniond(frame->LocalLevelFromEnu(sample.position_enu_m, &sample.geodetic)) * q,
                  drone_heading_deg)
            : GimbalFromWorldFromCamera(sample.world_from_camera, drone_heading_deg);
  sample.drone_heading_deg = g.drone_heading_deg;
  sample.gimbal_pitch_deg = g.gimbal_pitch_deg;
  sample.gimbal_roll_deg = g.gimbal_roll_deg;
  sample.gimbal_yaw_deg = g.gimbal_yaw_deg;
}

}  // namespace cinepath
