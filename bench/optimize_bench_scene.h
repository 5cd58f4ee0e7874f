// The optimize benchmarks' inputs (bench/optimize_bench.cc, bench/optimize_vs_ipopt.cc): a 60 s ORBIT at
// 30 fps (1,801 samples) around a walking subject with a framing goal and a background-blur goal, and a
// height field of rolling hills on a regular grid, 2 (n-1)^2 triangles over 2 km.
#pragma once

#include <cmath>
#include <string>

#include "core/json.h"
#include "core/trajectory.h"
#include "scene/scene_mesh.h"
#include "shots/planner.h"
#include "shots/shot_list.h"

namespace cinepath::bench {

inline double TerrainUpM(double e, double n) {
  return 6 * std::sin(e / 97.0) * std::cos(n / 131.0) + 2.5 * std::sin((e + n) / 41.0) + 0.8 * std::cos(e / 13.0);
}

inline scene::SceneMesh Terrain(size_t faces) {
  const int n = static_cast<int>(std::sqrt(faces / 2.0)) + 1;
  const double size_m = 2000, step = size_m / (n - 1);
  scene::SceneMesh mesh;
  mesh.positions_enu_m.reserve(size_t(n) * n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double e = -size_m / 2 + i * step, nn = -size_m / 2 + j * step;
      mesh.positions_enu_m.emplace_back(e, nn, TerrainUpM(e, nn));
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const uint32_t a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      mesh.faces.push_back({a, b, d});
      mesh.faces.push_back({a, d, c});
    }
  }
  return mesh;
}

inline Trajectory SixtySecondShot() {
  const std::string shots = R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "width_px": 3840, "height_px": 2160, "min_focal_length_mm": 24,
               "max_focal_length_mm": 120, "min_f_number": 1.4, "max_f_number": 16},
    "drone": "px4-multirotor",
    "actors": [{"name": "walker", "height_m": 1.8, "keyframes": [
      {"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 30, "position_enu_m": [40, 20, 0]},
      {"time_s": 60, "position_enu_m": [60, 70, 0]}]}],
    "shots": [{"name": "orbit", "type": "ORBIT", "subject": "walker", "duration_s": 60, "radius_m": 40,
               "height_m": 15, "turns": 0.5, "easing": "smootherstep",
               "lens": {"frame_height_fraction": 0.15, "background_blur_px": 12, "f_number": 4}}]})";
  return shots::PlanShots(shots::ParseShotList(Json::parse(shots), "bench_shots.json"));
}

}  // namespace cinepath::bench
