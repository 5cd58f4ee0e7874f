#include "core/three_frame.h"

#include <numbers>

#include "core/optics.h"

namespace cinepath {

Eigen::Vector3d ThreeFromEnu(const Eigen::Vector3d& enu_m) { return {enu_m.x(), enu_m.z(), -enu_m.y()}; }

Eigen::Vector3d EnuFromThree(const Eigen::Vector3d& three) { return {three.x(), -three.z(), three.y()}; }

Eigen::Quaterniond ThreeCameraFromWorldFromCamera(const Eigen::Quaterniond& world_from_camera) {
  Eigen::Matrix3d three_from_enu;
  three_from_enu << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  const Eigen::Matrix3d camera_from_three_camera = Eigen::Vector3d(1, -1, -1).asDiagonal();
  const Eigen::Matrix3d rotation =
      three_from_enu * world_from_camera.normalized().toRotationMatrix() * camera_from_three_camera;
  Eigen::Quaterniond q(rotation);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return q;
}

double VerticalFieldOfViewDeg(const CameraSpec& camera, double focal_length_mm) {
  return FieldOfViewRad(camera.image_extent_mm().height_mm, focal_length_mm) * 180.0 / std::numbers::pi;
}

}  // namespace cinepath
