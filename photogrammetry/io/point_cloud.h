// A point cloud handed from the readers / georeferencing to surface reconstruction.
// Positions are double precision in whatever frame the producer states (ENU metres after
// georeferencing): float32 only at final export (float32 ENU far from the origin quantizes vertices into stripes).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace cinepath::photogrammetry {

struct PointCloud {
  std::vector<Eigen::Vector3d> positions_m;
  std::vector<std::array<uint8_t, 3>> colors_rgb;  // empty, or one per point
  std::vector<Eigen::Vector3d> normals;            // empty, or one unit normal per point
  std::vector<double> reprojection_error_px;       // empty, or one per point (COLMAP ERROR)
  // Which cameras saw each point (COLMAP tracks): indices into camera_centers_m. Empty, or one list
  // per point. Used to orient normals toward the cameras and to drop short tracks.
  std::vector<Eigen::Vector3d> camera_centers_m;
  std::vector<std::vector<uint32_t>> observers;

  size_t size() const { return positions_m.size(); }
  bool has_colors() const { return !colors_rgb.empty(); }
  bool has_normals() const { return !normals.empty(); }
};

}  // namespace cinepath::photogrammetry
