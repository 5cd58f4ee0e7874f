// A registered photo as the texturing sees it: its COLMAP camera (model, parameters, size) and its pose
// in the scene frame (ENU metres after georeferencing), with the projection of a scene point to a pixel
// through the full camera model, distortion included (camera_models.h).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "photogrammetry/io/colmap_model.h"

namespace cinepath::photogrammetry {

class TextureView {
 public:
  TextureView() = default;
  // `image` posed in the frame of the mesh (e.g. ModelGeoreference::model_enu). InputError naming the
  // image when its camera model is unknown.
  TextureView(const ColmapImage& image, const ColmapCamera& camera);

  const std::string& name() const { return name_; }
  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  const Eigen::Vector3d& centre_m() const { return centre_m_; }
  const Eigen::Matrix3d& cam_from_world() const { return cam_from_world_; }
  const Eigen::Vector3d& cam_from_world_translation() const { return cam_from_world_translation_; }
  int model_id() const { return model_id_; }
  const std::vector<double>& params() const { return params_; }

  // The pixel (COLMAP convention: the upper-left pixel's centre is (0.5, 0.5)) where `world_m` appears,
  // and its depth along the optical axis. False behind the camera, and beyond the field of view the
  // image covers (a radius 10 % past its corners), where radial polynomials fold back onto the image.
  bool Project(const Eigen::Vector3d& world_m, Eigen::Vector2d* pixel, double* depth_m = nullptr) const;
  // Whether a pixel position lies in the image, at least `margin_px` from its border.
  bool Inside(const Eigen::Vector2d& pixel, double margin_px) const {
    return pixel.x() >= margin_px && pixel.y() >= margin_px && pixel.x() <= width_px_ - margin_px &&
           pixel.y() <= height_px_ - margin_px;
  }
  // Pixels per metre at `world_m` for a surface facing the camera (focal length over depth).
  double PixelsPerMetre(double depth_m) const { return focal_px_ / depth_m; }

 private:
  std::string name_;
  int model_id_ = 0;
  std::vector<double> params_;
  int width_px_ = 0, height_px_ = 0;
  double focal_px_ = 0;
  double max_radius2_ = 0;  // squared normalized radius past which Project refuses
  Eigen::Matrix3d cam_from_world_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d cam_from_world_translation_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d centre_m_ = Eigen::Vector3d::Zero();
};

}  // namespace cinepath::photogrammetry
