#include "photogrammetry/texture/texture_view.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "photogrammetry/georef/camera_models.h"

namespace cinepath::photogrammetry {

TextureView::TextureView(const ColmapImage& image, const ColmapCamera& camera)
    : name_(image.name),
      model_id_(camera.model_id),
      params_(camera.params),
      width_px_(int(camera.width_px)),
      height_px_(int(camera.height_px)) {
  if (!IsKnownCameraModel(model_id_) || int(params_.size()) != CameraModelNumParams(model_id_)) {
    throw InputError(Located(image.name, "camera " + std::to_string(camera.camera_id) + ": unknown camera model"));
  }
  cam_from_world_ = image.cam_from_world_rotation.normalized().toRotationMatrix();
  cam_from_world_translation_ = image.cam_from_world_translation;
  centre_m_ = image.ProjectionCenter();
  const std::vector<int> focal = CameraModelFocalIndices(model_id_);
  focal_px_ = focal.size() == 2 ? 0.5 * (params_[focal[0]] + params_[focal[1]]) : params_[focal[0]];
  // The widest normalized radius the image shows: its corners, undistorted.
  double r2 = 0;
  for (const auto& [x, y] : {std::pair<double, double>{0, 0},
                             {double(width_px_), 0},
                             {0, double(height_px_)},
                             {double(width_px_), double(height_px_)}}) {
    double u = 0, v = 0;
    if (PixelToNormalized(model_id_, params_, x, y, &u, &v)) r2 = std::max(r2, u * u + v * v);
  }
  if (r2 <= 0) {  // the corners did not converge: fall back on the pinhole field of view
    const double hx = 0.5 * width_px_ / focal_px_, hy = 0.5 * height_px_ / focal_px_;
    r2 = hx * hx + hy * hy;
  }
  max_radius2_ = 1.21 * r2;
}

bool TextureView::Project(const Eigen::Vector3d& world_m, Eigen::Vector2d* pixel, double* depth_m) const {
  const Eigen::Vector3d c = cam_from_world_ * world_m + cam_from_world_translation_;
  if (!(c.z() > 1e-6)) return false;
  const double u = c.x() / c.z(), v = c.y() / c.z();
  if (u * u + v * v > max_radius2_) return false;
  double x = 0, y = 0;
  if (!ProjectNormalizedToPixel(model_id_, params_.data(), u, v, &x, &y)) return false;
  if (!std::isfinite(x) || !std::isfinite(y)) return false;
  *pixel = Eigen::Vector2d(x, y);
  if (depth_m) *depth_m = c.z();
  return true;
}

}  // namespace cinepath::photogrammetry
