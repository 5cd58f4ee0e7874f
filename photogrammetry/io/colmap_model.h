// A COLMAP sparse model in memory: cameras, registered images, 3D points with tracks.
//
// Conventions are COLMAP's (doc/format.rst): an image's pose (cam_from_world_rotation,
// cam_from_world_translation) maps world to camera, x_cam = R x_world + t; the quaternion is
// Hamilton, (w, x, y, z), normalized on reading; the camera centre is C = -R^T t. Camera axes: x right,
// y down, z forward. Ids are COLMAP's (unordered, non-contiguous); containers are ordered maps so that
// iteration is deterministic.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cinepath::photogrammetry {

inline constexpr uint64_t kInvalidPoint3DId = std::numeric_limits<uint64_t>::max();

struct ColmapCamera {
  uint32_t camera_id = 0;
  int model_id = 0;  // see camera_models.h
  uint64_t width_px = 0;
  uint64_t height_px = 0;
  std::vector<double> params;  // CameraModelNumParams(model_id) values

  bool operator==(const ColmapCamera&) const = default;
};

struct ColmapImage {
  uint32_t image_id = 0;
  Eigen::Quaterniond cam_from_world_rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d cam_from_world_translation = Eigen::Vector3d::Zero();
  uint32_t camera_id = 0;
  std::string name;
  std::vector<Eigen::Vector2d> points2d_px;  // keypoints, COLMAP pixel convention
  std::vector<uint64_t> point3d_ids;         // one per keypoint; kInvalidPoint3DId = none

  Eigen::Vector3d ProjectionCenter() const {
    return -(cam_from_world_rotation.toRotationMatrix().transpose() * cam_from_world_translation);
  }
  bool operator==(const ColmapImage& o) const {
    return image_id == o.image_id && cam_from_world_rotation.coeffs() == o.cam_from_world_rotation.coeffs() &&
           cam_from_world_translation == o.cam_from_world_translation && camera_id == o.camera_id && name == o.name &&
           points2d_px == o.points2d_px && point3d_ids == o.point3d_ids;
  }
};

struct ColmapTrackElement {
  uint32_t image_id = 0;
  uint32_t point2d_idx = 0;
  bool operator==(const ColmapTrackElement&) const = default;
};

struct ColmapPoint3D {
  uint64_t point3d_id = 0;
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();
  std::array<uint8_t, 3> rgb = {0, 0, 0};
  double error_px = 0;  // mean reprojection error; COLMAP writes -1 when not computed
  std::vector<ColmapTrackElement> track;

  bool operator==(const ColmapPoint3D&) const = default;
};

struct ColmapModel {
  std::map<uint32_t, ColmapCamera> cameras;
  std::map<uint32_t, ColmapImage> images;
  std::map<uint64_t, ColmapPoint3D> points3d;

  bool operator==(const ColmapModel&) const = default;
};

}  // namespace cinepath::photogrammetry
