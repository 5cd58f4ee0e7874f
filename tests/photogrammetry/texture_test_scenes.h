// Synthetic scenes for the texturing tests: a flat ground of known colours (a checkerboard) and photos
// of it rendered exactly through a COLMAP camera model, distortion included.
#pragma once

#include <cmath>
#include <functional>

#include <Eigen/Geometry>

#include "photogrammetry/georef/camera_models.h"
#include "photogrammetry/io/colmap_model.h"
#include "photogrammetry/io/photo_image.h"
#include "photogrammetry/mesh/triangle_mesh.h"
#include "photogrammetry/texture/texture_view.h"

namespace cinepath::photogrammetry::testing {

// An n x n grid of squares of `cell_m` at height z, two faces per square, counter-clockwise from above.
inline TriangleMesh GroundGrid(int n, double cell_m, double z = 0, double x0 = 0, double y0 = 0) {
  TriangleMesh mesh;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.vertices_m.emplace_back(x0 + i * cell_m, y0 + j * cell_m, z);
      mesh.colors_rgb.push_back({10, 200, 30});
    }
  }
  auto at = [n](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return mesh;
}

// The ground's true colour: 1 m squares, sRGB 220 or 30 in red, the opposite in blue, green 128.
inline Eigen::Vector3f Checker(const Eigen::Vector3d& p) {
  const bool odd = (int(std::floor(p.x())) + int(std::floor(p.y()))) % 2 != 0;
  return odd ? Eigen::Vector3f(220, 128, 30) : Eigen::Vector3f(30, 128, 220);
}

// A camera at `centre` looking straight down (image x = east, image y = south).
inline ColmapImage NadirImage(const Eigen::Vector3d& centre, const std::string& name) {
  ColmapImage image;
  image.name = name;
  image.camera_id = 1;
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  image.cam_from_world_rotation = Eigen::Quaterniond(r);
  image.cam_from_world_translation = -r * centre;
  return image;
}

// A camera at `centre` looking at `target` (image y roughly down the world's z).
inline ColmapImage LookAtImage(const Eigen::Vector3d& centre, const Eigen::Vector3d& target, const std::string& name) {
  const Eigen::Vector3d z = (target - centre).normalized();
  Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ());
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d r;
  r.row(0) = x;
  r.row(1) = y;
  r.row(2) = z;
  ColmapImage image;
  image.name = name;
  image.camera_id = 1;
  image.cam_from_world_rotation = Eigen::Quaterniond(r);
  image.cam_from_world_translation = -r * centre;
  return image;
}

inline ColmapCamera Camera(int model_id, std::vector<double> params, int width, int height) {
  ColmapCamera camera;
  camera.camera_id = 1;
  camera.model_id = model_id;
  camera.params = std::move(params);
  camera.width_px = uint64_t(width);
  camera.height_px = uint64_t(height);
  return camera;
}

// The photo of the plane z = `ground_z` seen by `image` through `camera`: each pixel's ray (the
// distortion inverted) meets the plane; `color` gives the sRGB colour there, times `gain`.
inline RgbImage RenderPlanePhoto(const ColmapImage& image, const ColmapCamera& camera, double ground_z,
                                 const std::function<Eigen::Vector3f(const Eigen::Vector3d&)>& color,
                                 float gain = 1.0f) {
  RgbImage photo;
  photo.width = int(camera.width_px);
  photo.height = int(camera.height_px);
  photo.rgb.assign(size_t(photo.width) * photo.height * 3, 0);
  const Eigen::Matrix3d world_from_cam = image.cam_from_world_rotation.toRotationMatrix().transpose();
  const Eigen::Vector3d centre = image.ProjectionCenter();
  for (int y = 0; y < photo.height; ++y) {
    for (int x = 0; x < photo.width; ++x) {
      double u = 0, v = 0;
      if (!PixelToNormalized(camera.model_id, camera.params, x + 0.5, y + 0.5, &u, &v)) continue;
      const Eigen::Vector3d d = world_from_cam * Eigen::Vector3d(u, v, 1);
      if (std::abs(d.z()) < 1e-9) continue;
      const double t = (ground_z - centre.z()) / d.z();
      if (t <= 0) continue;
      const Eigen::Vector3f c = color(centre + t * d);
      for (int k = 0; k < 3; ++k) {
        const float linear = LinearFromSrgb(uint8_t(std::lround(c[k]))) * gain;
        photo.At(x, y)[k] = SrgbFromLinear(linear);
      }
    }
  }
  return photo;
}

}  // namespace cinepath::photogrammetry::testing
