#include "preview/thin_lens_camera.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/optics.h"

namespace cinepath::preview {

ThinLensCamera::ThinLensCamera(const CameraSpec& camera, int width_px, int height_px, double focal_length_mm,
                               double f_number, double focus_distance_m)
    : width_px_(width_px),
      height_px_(height_px),
      sensor_width_mm_(camera.sensor_width_mm),
      image_height_mm_(ImageExtentOnSensorMm(camera.sensor_width_mm, width_px, height_px).height_mm),
      focal_length_mm_(focal_length_mm),
      f_number_(f_number),
      focus_distance_m_(focus_distance_m),
      lens_radius_m_(focal_length_mm / f_number / 2 / 1000),
      lens_(focal_length_mm / 1000.0, f_number, 1.0 / focus_distance_m),
      ray_traced_(std::isinf(focus_distance_m) ? 1.0 : (focus_distance_m - focal_length_mm / 1000) / focus_distance_m) {
  ValidateFocalLengthMm(focal_length_mm);
  ValidateFNumber(f_number);
  if (!std::isinf(focus_distance_m)) ValidateFocusDistanceM(focus_distance_m, focal_length_mm);
}

void ThinLensCamera::CameraRayInCamera(double x_px, double y_px, double lens_u, double lens_v,
                                       Eigen::Vector3d* origin_cam, Eigen::Vector3d* direction_cam) const {
  const Eigen::Vector3d pinhole(SlopeX(x_px), SlopeY(y_px), 1.0);
  *origin_cam = Eigen::Vector3d::Zero();
  *direction_cam = pinhole;
  if (lens_u != 0 || lens_v != 0) {
    *origin_cam = Eigen::Vector3d(lens_u * lens_radius_m_, lens_v * lens_radius_m_, 0);
    // Toward the point on the plane of focus; at infinity, parallel to the pinhole ray.
    if (!std::isinf(focus_distance_m_)) *direction_cam = pinhole * focus_distance_m_ - *origin_cam;
  }
}

namespace {

// The ray from the camera frame's origin_cam along direction_cam, in ENU; `rotation` is a quaternion or a
// matrix. A pinhole ray starts at the camera's centre (the rotation of the zero vector is zero: the same
// bytes as rotating it).
template <typename Rotation>
CameraRay InWorld(const Eigen::Vector3d& position_enu_m, const Rotation& world_from_camera,
                  const Eigen::Vector3d& origin_cam, const Eigen::Vector3d& direction_cam) {
  const Eigen::Vector3d origin =
      origin_cam.isZero(0) ? position_enu_m : Eigen::Vector3d(position_enu_m + world_from_camera * origin_cam);
  return {origin, (world_from_camera * direction_cam).normalized()};
}

}  // namespace

CameraRay ThinLensCamera::Ray(const CameraPose& pose, double x_px, double y_px, double lens_u, double lens_v) const {
  Eigen::Vector3d origin_cam, direction_cam;
  CameraRayInCamera(x_px, y_px, lens_u, lens_v, &origin_cam, &direction_cam);
  return InWorld(pose.position_enu_m, pose.world_from_camera, origin_cam, direction_cam);
}

CameraRay ThinLensCamera::Ray(const CameraFrame& frame, double x_px, double y_px, double lens_u, double lens_v) const {
  Eigen::Vector3d origin_cam, direction_cam;
  CameraRayInCamera(x_px, y_px, lens_u, lens_v, &origin_cam, &direction_cam);
  return InWorld(frame.position_enu_m, frame.world_from_camera, origin_cam, direction_cam);
}

PinholeRays::PinholeRays(const ThinLensCamera& camera, const CameraFrame& frame)
    : origin_enu_m_(frame.position_enu_m),
      world_from_camera_(frame.world_from_camera),
      slope_x_(size_t(std::max(0, camera.width_px()))),
      slope_y_(size_t(std::max(0, camera.height_px()))) {
  for (size_t x = 0; x < slope_x_.size(); ++x) slope_x_[x] = camera.SlopeX(double(x) + 0.5);
  for (size_t y = 0; y < slope_y_.size(); ++y) slope_y_[y] = camera.SlopeY(double(y) + 0.5);
}

Eigen::Vector2d ThinLensCamera::Project(const CameraPose& pose, const Eigen::Vector3d& point_enu_m,
                                        double* depth_m) const {
  return ImagePoint(pose.world_from_camera.conjugate() * (point_enu_m - pose.position_enu_m), depth_m);
}

Eigen::Vector2d ThinLensCamera::Project(const CameraFrame& frame, const Eigen::Vector3d& point_enu_m,
                                        double* depth_m) const {
  return ImagePoint(frame.world_from_camera.transpose() * (point_enu_m - frame.position_enu_m), depth_m);
}

Eigen::Vector2d ThinLensCamera::ImagePoint(const Eigen::Vector3d& p, double* depth_m) const {
  *depth_m = p.z();
  const double x_mm = p.x() / p.z() * focal_length_mm_;
  const double y_mm = p.y() / p.z() * focal_length_mm_;
  return {(x_mm / sensor_width_mm_ + 0.5) * width_px_, (y_mm / image_height_mm_ + 0.5) * height_px_};
}

double ThinLensCamera::BlurPx(double depth_m) const {
  if (!(depth_m > focal_length_mm_ / 1000)) return 0;
  // Core's blur circle of the lens (its terms worked out once, in the constructor; the lens was checked
  // there and the depth above): the same bits as BlurCircleDiameterM, three divisions a pixel instead of seven.
  const double c_mm = lens_.BlurCircleDiameterM(1.0 / depth_m) * 1000.0;
  return c_mm * ray_traced_ * pixels_per_mm();
}

Eigen::Vector2d ConcentricDisk(double u1, double u2) {
  const double a = 2 * u1 - 1, b = 2 * u2 - 1;
  if (a == 0 && b == 0) return {0, 0};
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = M_PI / 4 * (b / a);
  } else {
    r = b;
    phi = M_PI / 2 - M_PI / 4 * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

size_t SampleAfter(const std::vector<TrajectorySample>& samples, size_t n, double time_s, size_t hint) {
  const auto later = [](double t, const TrajectorySample& s) { return t < s.time_s; };
  const size_t lo = std::min(hint > 0 ? hint - 1 : 0, n), hi = std::min(hint + 3, n);
  const auto begin = samples.begin();
  if ((lo == 0 || samples[lo - 1].time_s <= time_s) && (hi == n || samples[hi].time_s > time_s)) {
    return size_t(std::upper_bound(begin + long(lo), begin + long(hi), time_s, later) - begin);
  }
  return size_t(std::upper_bound(begin, begin + long(n), time_s, later) - begin);
}

CameraPose PoseAt(const Trajectory& plan, double time_s, size_t hint) {
  const auto& samples = plan.samples;
  if (time_s <= samples.front().time_s) return {samples.front().position_enu_m, samples.front().world_from_camera};
  if (time_s >= samples.back().time_s) return {samples.back().position_enu_m, samples.back().world_from_camera};
  const size_t next = SampleAfter(samples, samples.size(), time_s, hint);
  const TrajectorySample& b = samples[next];
  const TrajectorySample& a = samples[next - 1];
  const double span = b.time_s - a.time_s;
  const double w = span > 0 ? (time_s - a.time_s) / span : 0;
  return {a.position_enu_m + w * (b.position_enu_m - a.position_enu_m),
          a.world_from_camera.slerp(w, b.world_from_camera).normalized()};
}

}  // namespace cinepath::preview
