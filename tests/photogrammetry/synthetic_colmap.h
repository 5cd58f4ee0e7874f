// Test support: synthetic COLMAP scenes generated in code with a known ENU transform (as COLMAP's own
// scene/synthetic does), and a COLMAP-format writer (text and binary, the layouts of
// colmap@3.8:src/base/reconstruction.cc Write*Text / Write*Binary).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <random>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "photogrammetry/georef/camera_models.h"
#include "photogrammetry/georef/georeference.h"
#include "photogrammetry/io/colmap_model.h"

namespace cinepath::photogrammetry::testing {

// ---------------------------------------------------------------------------------------------
// Writers.

inline std::string ColmapCamerasText(const ColmapModel& m) {
  std::ostringstream os;
  os << std::setprecision(17);
  os << "# Camera list with one line of data per camera:\n#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n";
  for (const auto& [id, c] : m.cameras) {
    os << id << " " << CameraModelName(c.model_id) << " " << c.width_px << " " << c.height_px;
    for (double p : c.params) os << " " << p;
    os << "\n";
  }
  return os.str();
}

inline std::string ColmapImagesText(const ColmapModel& m) {
  std::ostringstream os;
  os << std::setprecision(17);
  os << "# Image list with two lines of data per image:\n";
  for (const auto& [id, im] : m.images) {
    const auto& q = im.cam_from_world_rotation;
    const auto& t = im.cam_from_world_translation;
    os << id << " " << q.w() << " " << q.x() << " " << q.y() << " " << q.z() << " " << t.x() << " " << t.y() << " "
       << t.z() << " " << im.camera_id << " " << im.name << "\n";
    for (size_t k = 0; k < im.points2d_px.size(); ++k) {
      if (k) os << " ";
      os << im.points2d_px[k].x() << " " << im.points2d_px[k].y() << " ";
      if (im.point3d_ids[k] == kInvalidPoint3DId) {
        os << -1;
      } else {
        os << im.point3d_ids[k];
      }
    }
    os << "\n";
  }
  return os.str();
}

inline std::string ColmapPoints3DText(const ColmapModel& m) {
  std::ostringstream os;
  os << std::setprecision(17);
  os << "# 3D point list with one line of data per point:\n";
  for (const auto& [id, p] : m.points3d) {
    os << id << " " << p.xyz.x() << " " << p.xyz.y() << " " << p.xyz.z() << " " << int(p.rgb[0]) << " " << int(p.rgb[1])
       << " " << int(p.rgb[2]) << " " << p.error_px;
    for (const auto& e : p.track) os << " " << e.image_id << " " << e.point2d_idx;
    os << "\n";
  }
  return os.str();
}

template <typename T>
void Put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

inline std::string ColmapCamerasBinary(const ColmapModel& m) {
  std::string out;
  Put<uint64_t>(out, m.cameras.size());
  for (const auto& [id, c] : m.cameras) {
    Put<uint32_t>(out, id);
    Put<int32_t>(out, c.model_id);
    Put<uint64_t>(out, c.width_px);
    Put<uint64_t>(out, c.height_px);
    for (double p : c.params) Put<double>(out, p);
  }
  return out;
}

inline std::string ColmapImagesBinary(const ColmapModel& m) {
  std::string out;
  Put<uint64_t>(out, m.images.size());
  for (const auto& [id, im] : m.images) {
    Put<uint32_t>(out, id);
    const auto& q = im.cam_from_world_rotation;
    for (double v : {q.w(), q.x(), q.y(), q.z()}) Put<double>(out, v);
    for (int k = 0; k < 3; ++k) Put<double>(out, im.cam_from_world_translation[k]);
    Put<uint32_t>(out, im.camera_id);
    out.append(im.name);
    out.push_back('\0');
    Put<uint64_t>(out, im.points2d_px.size());
    for (size_t k = 0; k < im.points2d_px.size(); ++k) {
      Put<double>(out, im.points2d_px[k].x());
      Put<double>(out, im.points2d_px[k].y());
      Put<uint64_t>(out, im.point3d_ids[k]);
    }
  }
  return out;
}

inline std::string ColmapPoints3DBinary(const ColmapModel& m) {
  std::string out;
  Put<uint64_t>(out, m.points3d.size());
  for (const auto& [id, p] : m.points3d) {
    Put<uint64_t>(out, id);
    for (int k = 0; k < 3; ++k) Put<double>(out, p.xyz[k]);
    for (int k = 0; k < 3; ++k) Put<uint8_t>(out, p.rgb[k]);
    Put<double>(out, p.error_px);
    Put<uint64_t>(out, p.track.size());
    for (const auto& e : p.track) {
      Put<uint32_t>(out, e.image_id);
      Put<uint32_t>(out, e.point2d_idx);
    }
  }
  return out;
}

inline void WriteFile(const std::filesystem::path& path, const std::string& data) {
  std::ofstream f(path, std::ios::binary);
  f.write(data.data(), static_cast<std::streamsize>(data.size()));
}

inline void WriteColmapText(const ColmapModel& m, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  WriteFile(dir / "cameras.txt", ColmapCamerasText(m));
  WriteFile(dir / "images.txt", ColmapImagesText(m));
  WriteFile(dir / "points3D.txt", ColmapPoints3DText(m));
}

inline void WriteColmapBinary(const ColmapModel& m, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  WriteFile(dir / "cameras.bin", ColmapCamerasBinary(m));
  WriteFile(dir / "images.bin", ColmapImagesBinary(m));
  WriteFile(dir / "points3D.bin", ColmapPoints3DBinary(m));
}

// ---------------------------------------------------------------------------------------------
// Synthetic nadir drone survey.

struct SyntheticOptions {
  int model_id = static_cast<int>(CameraModelId::kSimpleRadial);
  std::vector<double> params = {900, 800, 450, -0.02};  // for a 1600 x 900 camera
  int width_px = 1600, height_px = 900;
  int rows = 3, cols = 6;       // camera grid (flight lines x photos per line)
  double spacing_m = 15;        // between photos and lines
  double flying_height_m = 40;  // above the mean ground
  double terrain_relief_m = 3;  // amplitude of the ground bumps
  int num_points = 1500;
  double pixel_noise_px = 0.3;
  uint64_t seed = 7;
  // The COLMAP frame: enu = enu_from_colmap(colmap).
  Similarity3 enu_from_colmap;
};

struct SyntheticScene {
  ColmapModel model;                                  // in the COLMAP frame
  ColmapModel model_enu;                              // the truth in ENU
  std::vector<Eigen::Vector3d> camera_centers_enu_m;  // by image index (image id = index + 1)
};

inline Similarity3 DefaultColmapFrame() {
  Similarity3 t;
  t.scale = 7.5;  // COLMAP units are arbitrary: 1 unit = 7.5 m
  t.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()));
  t.translation = {12.0, -30.0, 160.0};
  return t;
}

inline double SyntheticGroundHeight(double e, double n, double relief) {
  return relief * (std::sin(e / 9.0) * std::cos(n / 13.0) + 0.3 * std::sin((e + n) / 5.0));
}

inline SyntheticScene MakeSyntheticScene(const SyntheticOptions& o) {
  SyntheticScene scene;
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> noise(0.0, o.pixel_noise_px);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);

  ColmapCamera camera;
  camera.camera_id = 1;
  camera.model_id = o.model_id;
  camera.width_px = o.width_px;
  camera.height_px = o.height_px;
  camera.params = o.params;
  scene.model_enu.cameras[1] = camera;

  // Cameras: lawnmower grid, looking down (camera z = -up), x = east, y = south, small tilts.
  const double e0 = -0.5 * (o.cols - 1) * o.spacing_m, n0 = -0.5 * (o.rows - 1) * o.spacing_m;
  uint32_t image_id = 1;
  for (int r = 0; r < o.rows; ++r) {
    for (int c = 0; c < o.cols; ++c, ++image_id) {
      const Eigen::Vector3d center(e0 + c * o.spacing_m, n0 + r * o.spacing_m,
                                   o.flying_height_m + 0.5 * std::sin(1.3 * image_id));
      Eigen::Matrix3d cam_from_enu;
      cam_from_enu << 1, 0, 0, 0, -1, 0, 0, 0, -1;
      const Eigen::Matrix3d tilt = (Eigen::AngleAxisd(0.03 * std::sin(2.1 * image_id), Eigen::Vector3d::UnitX()) *
                                    Eigen::AngleAxisd(0.03 * std::cos(1.7 * image_id), Eigen::Vector3d::UnitY()))
                                       .toRotationMatrix();
      ColmapImage image;
      image.image_id = image_id;
      image.camera_id = 1;
      image.name = "IMG_" + std::to_string(1000 + image_id) + ".JPG";
      image.cam_from_world_rotation = Eigen::Quaterniond(tilt * cam_from_enu).normalized();
      image.cam_from_world_translation = -(image.cam_from_world_rotation * center);
      scene.model_enu.images[image_id] = image;
      scene.camera_centers_enu_m.push_back(center);
    }
  }

  // Points on the terrain, observed by every camera that sees them inside the image.
  const double half_e = -e0 + 15, half_n = -n0 + 12;
  uint64_t point_id = 1;
  for (int i = 0; i < o.num_points; ++i) {
    const double e = (2 * uniform(rng) - 1) * half_e;
    const double n = (2 * uniform(rng) - 1) * half_n;
    const Eigen::Vector3d x(e, n, SyntheticGroundHeight(e, n, o.terrain_relief_m));
    ColmapPoint3D point;
    point.point3d_id = point_id;
    point.xyz = x;
    point.rgb = {static_cast<uint8_t>(100 + i % 100), static_cast<uint8_t>(50 + i % 150), 30};
    point.error_px = o.pixel_noise_px;
    for (auto& [id, image] : scene.model_enu.images) {
      const Eigen::Vector3d xc = image.cam_from_world_rotation * x + image.cam_from_world_translation;
      if (xc.z() <= 0) continue;
      double px, py;
      ProjectNormalizedToPixel(o.model_id, o.params.data(), xc.x() / xc.z(), xc.y() / xc.z(), &px, &py);
      if (px < 0 || py < 0 || px >= o.width_px || py >= o.height_px) continue;
      point.track.push_back({id, static_cast<uint32_t>(image.points2d_px.size())});
      image.points2d_px.push_back({px + noise(rng), py + noise(rng)});
      image.point3d_ids.push_back(point_id);
    }
    if (point.track.size() < 2) {
      // Keep the keypoints but unlink them (COLMAP keeps unmatched keypoints with id -1).
      for (const auto& e2 : point.track)
        scene.model_enu.images[e2.image_id].point3d_ids[e2.point2d_idx] = kInvalidPoint3DId;
      continue;
    }
    scene.model_enu.points3d[point_id] = point;
    ++point_id;
  }

  // Into the COLMAP frame: colmap = enu_from_colmap^-1 (enu).
  const Similarity3 colmap_from_enu = o.enu_from_colmap.Inverse();
  scene.model = scene.model_enu;
  for (auto& [id, image] : scene.model.images) {
    const Eigen::Vector3d c = colmap_from_enu(image.ProjectionCenter());
    image.cam_from_world_rotation = (image.cam_from_world_rotation * colmap_from_enu.rotation.conjugate()).normalized();
    image.cam_from_world_translation = -(image.cam_from_world_rotation * c);
  }
  for (auto& [id, p] : scene.model.points3d) p.xyz = colmap_from_enu(p.xyz);
  return scene;
}

}  // namespace cinepath::photogrammetry::testing
