// Synthetic meshes and clouds for the surface tests (generated in code, no fixtures).
#pragma once

#include <cmath>
#include <cstdint>

#include <Eigen/Geometry>

#include "photogrammetry/point_cloud.h"
#include "photogrammetry/triangle_mesh.h"

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

}  // namespace cinepath::photogrammetry::testing
