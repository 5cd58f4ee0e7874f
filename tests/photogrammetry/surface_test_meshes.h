// Synthetic meshes and clouds for the surface tests (generated in code, no fixtures).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include <Eigen/Geometry>

#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry::testing {

// Smooth rolling terrain height (metres) at (e, n).
inline double TerrainHeightM(double e, double n) { return 3.0 * std::sin(e * 0.05) * std::cos(n * 0.04) + 0.02 * e; }

// A (cols × rows)-vertex grid with spacing_m, heights from TerrainHeightM, two CCW (seen from above)
// triangles per cell, colours varying with position.
inline TriangleMesh TerrainGrid(int cols, int rows, double spacing_m) {
  TriangleMesh mesh;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      const double e = i * spacing_m, n = j * spacing_m;
      mesh.vertices_m.emplace_back(e, n, TerrainHeightM(e, n));
      mesh.colors_rgb.push_back({static_cast<uint8_t>(i % 256), static_cast<uint8_t>(j % 256), 128});
    }
  }
  auto id = [cols](int i, int j) { return static_cast<uint32_t>(j * cols + i); };
  for (int j = 0; j + 1 < rows; ++j) {
    for (int i = 0; i + 1 < cols; ++i) {
      mesh.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return mesh;
}

// Points on the terrain with jitter-free positions, colours, and cameras 50 m above that see them.
inline PointCloud TerrainCloud(int cols, int rows, double spacing_m) {
  PointCloud cloud;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      // A deterministic sub-cell offset so the points are not on a lattice.
      const double e = (i + 0.3 * std::sin(1.7 * i + 0.3 * j)) * spacing_m;
      const double n = (j + 0.3 * std::cos(0.9 * i + 2.1 * j)) * spacing_m;
      cloud.positions_m.emplace_back(e, n, TerrainHeightM(e, n));
      cloud.colors_rgb.push_back({static_cast<uint8_t>(e > cols * spacing_m / 2 ? 200 : 20), 90,
                                  static_cast<uint8_t>(n > rows * spacing_m / 2 ? 200 : 20)});
      cloud.reprojection_error_px.push_back(0.5);
    }
  }
  for (int c = 0; c < 4; ++c) {
    cloud.camera_centers_m.emplace_back((c % 2 + 0.5) * cols * spacing_m / 2, (c / 2 + 0.5) * rows * spacing_m / 2,
                                        50.0);
  }
  cloud.observers.assign(cloud.size(), {0, 1, 2, 3});
  return cloud;
}

// An L of two bounded planes, as a box's floor and one wall: the floor z = 0 over [0, kLWidthM] ×
// [0, kLDepthM] and the wall y = 0 over [0, kLWidthM] × [0, kLHeightM], facing the floor; points every
// kLPitchM, jittered by up to 0.3 pitch, with normals, seen by three cameras in front of the wall.
constexpr double kLWidthM = 12.0, kLDepthM = 8.0, kLHeightM = 5.0, kLPitchM = 0.3;
inline PointCloud LCloud() {
  PointCloud cloud;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3 * kLPitchM, 0.3 * kLPitchM);
  auto add = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
    cloud.positions_m.push_back(p);
    cloud.normals.push_back(n);
    cloud.colors_rgb.push_back({120, 120, 120});
    cloud.reprojection_error_px.push_back(0.4);
  };
  for (double x = 0; x <= kLWidthM + 1e-9; x += kLPitchM) {
    for (double y = kLPitchM; y <= kLDepthM + 1e-9; y += kLPitchM) {
      add({std::clamp(x + jitter(rng), 0.0, kLWidthM), std::clamp(y + jitter(rng), 0.0, kLDepthM), 0}, {0, 0, 1});
    }
    for (double z = 0; z <= kLHeightM + 1e-9; z += kLPitchM) {
      add({std::clamp(x + jitter(rng), 0.0, kLWidthM), 0, std::clamp(z + jitter(rng), 0.0, kLHeightM)}, {0, 1, 0});
    }
  }
  // Cameras in front of the wall and above the floor.
  cloud.camera_centers_m = {{2, 20, 12}, {10, 20, 12}, {6, 14, 18}};
  cloud.observers.assign(cloud.size(), {0, 1, 2});
  return cloud;
}

}  // namespace cinepath::photogrammetry::testing
