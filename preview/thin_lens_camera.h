// The camera of one frame as render traces it: a thin lens with the plan's filmback, focal length,
// focus distance and f-number, posed by world_from_camera (camera x right, y down, z forward; ENU).
//
// Sensor fit (core/optics.h, ImageExtentOnSensorMm): the image spans the sensor's full width w, and
// w * H / W of its height. Pixel (x, y) (continuous, 0..W, 0..H, y down) looks along
//   d_cam = ((x/W - 1/2) w, (y/H - 1/2) w H/W, f) / f.
// Thin lens (pbrt's convention, as Cycles and Mitsuba): a point on the lens disk of diameter
// A = f/N, in the plane z = 0, aims at the point s * d_cam on the plane of focus z = s (s = infinity
// keeps d_cam). A point at depth z is then blurred over c * (s - f)/s on the sensor, c being core's
// blur circle c = (f^2/N)|1/s - 1/z|/(1 - f/s) (docs/render.md, "Blur convention").
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/optics.h"
#include "core/trajectory.h"

namespace cinepath::preview {

struct CameraRay {
  Eigen::Vector3d origin_enu_m;
  Eigen::Vector3d direction_enu;  // unit
};

struct CameraPose {
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond world_from_camera = Eigen::Quaterniond::Identity();
};

// A pose with its rotation as a matrix: the rays of one instant (a frame's pinhole pass, every ray of a
// frame without motion blur) rotate by it with 9 multiplications instead of the quaternion's ~30.
struct CameraFrame {
  explicit CameraFrame(const CameraPose& pose)
      : position_enu_m(pose.position_enu_m), world_from_camera(pose.world_from_camera.toRotationMatrix()) {}
  Eigen::Vector3d position_enu_m;
  Eigen::Matrix3d world_from_camera;
};

class ThinLensCamera {
 public:
  // InputError for a focal length, f-number or focus distance core/optics.h refuses.
  ThinLensCamera(const CameraSpec& camera, int width_px, int height_px, double focal_length_mm, double f_number,
                 double focus_distance_m);

  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  double focal_length_mm() const { return focal_length_mm_; }
  double f_number() const { return f_number_; }
  double focus_distance_m() const { return focus_distance_m_; }

  // The ray through image point (x, y) from lens point (lens_u, lens_v) on the unit disk (0, 0 is the
  // centre: a pinhole ray), for the camera at `pose`.
  CameraRay Ray(const CameraPose& pose, double x_px, double y_px, double lens_u = 0, double lens_v = 0) const;
  // The same ray for the camera at `frame` (its rotation as a matrix: the same ray to ~1e-16).
  CameraRay Ray(const CameraFrame& frame, double x_px, double y_px, double lens_u = 0, double lens_v = 0) const;

  // The pinhole ray's direction in the camera frame through image point (x, y) is (slope x, slope y, 1).
  double SlopeX(double x_px) const { return (x_px / width_px_ - 0.5) * sensor_width_mm_ / focal_length_mm_; }
  double SlopeY(double y_px) const { return (y_px / height_px_ - 0.5) * image_height_mm_ / focal_length_mm_; }

  // Where an ENU point lands in the image (continuous pixels) through the lens centre, and its depth
  // along the optical axis; depth <= 0 means behind the camera.
  Eigen::Vector2d Project(const CameraPose& pose, const Eigen::Vector3d& point_enu_m, double* depth_m) const;
  // The same through the camera at `frame` (the rotation's transpose: 9 multiplications, the same point to
  // ~1e-16): for many points of one instant, such as every pixel's at the shutter's ends.
  Eigen::Vector2d Project(const CameraFrame& frame, const Eigen::Vector3d& point_enu_m, double* depth_m) const;

  // The blur-circle diameter in pixels these rays give a point at depth z (the convention above);
  // 0 on the plane of focus.
  double BlurPx(double depth_m) const;

  // Pixels per millimetre on the sensor (W / w).
  double pixels_per_mm() const { return width_px_ / sensor_width_mm_; }

 private:
  // A point in the camera's frame -> the image (and its depth), for both Projects.
  Eigen::Vector2d ImagePoint(const Eigen::Vector3d& point_cam_m, double* depth_m) const;

  int width_px_;
  int height_px_;
  double sensor_width_mm_;
  double image_height_mm_;
  double focal_length_mm_;
  double f_number_;
  double focus_distance_m_;  // +inf = infinity
  double lens_radius_m_;
  // BlurPx's terms that depend on the lens alone.
  FocusedLens<double> lens_;
  double ray_traced_;  // (s - f) / s: the rays' convention (above); 1 at infinity
  // The ray's start (on the lens, z = 0) and direction in the camera frame.
  void CameraRayInCamera(double x_px, double y_px, double lens_u, double lens_v, Eigen::Vector3d* origin_cam,
                         Eigen::Vector3d* direction_cam) const;
};

// The pinhole rays through the pixel centres of one frame: Ray(frame, x + 1/2, y + 1/2) to the bit, in
// fewer instructions: each column's and row's slope is worked out once, and the direction is rotated by
// the same expression as Ray's (not split into per-column and per-row terms: Eigen sums the third
// coordinate's products in another order than the first two's, so a split would change the last bit).
class PinholeRays {
 public:
  PinholeRays(const ThinLensCamera& camera, const CameraFrame& frame);
  CameraRay At(int x, int y) const {
    return {origin_enu_m_,
            (world_from_camera_ * Eigen::Vector3d(slope_x_[size_t(x)], slope_y_[size_t(y)], 1.0)).normalized()};
  }

 private:
  Eigen::Vector3d origin_enu_m_;
  Eigen::Matrix3d world_from_camera_;
  std::vector<double> slope_x_;  // SlopeX(x + 1/2) of each column
  std::vector<double> slope_y_;  // SlopeY(y + 1/2) of each row
};

// Concentric map of [0,1)^2 onto the unit disk (Shirley and Chiu 1997): uniform and low-distortion,
// so stratified lens samples stay stratified.
Eigen::Vector2d ConcentricDisk(double u1, double u2);

// The index of the first of samples[0, n) later than t (std::upper_bound on time), looking first
// around `hint` (samples hint-1 .. hint+2: a ray inside sample hint's shutter interval finds it there
// without a binary search over the whole plan). The same index whatever the hint.
size_t SampleAfter(const std::vector<TrajectorySample>& samples, size_t n, double time_s, size_t hint);

// The pose at time t, between the samples around it: position linear, orientation slerp; clamped to
// the plan's first and last sample. `hint`: a sample index near t (SampleAfter), or none.
CameraPose PoseAt(const Trajectory& plan, double time_s, size_t hint = 0);

}  // namespace cinepath::preview
