// `cinepath optimize` on a 60 s shot at 30 fps (1,801 samples) with the lens free and depth-of-field
// goals: the time of each preset without a mesh, and against a 1 M-face terrain (the corridor crop and
// both index builds included), with the final cost, the worst limit and the least clearance.
//   optimize_bench [--faces N]
// The terrain: a height field of rolling hills on a regular grid, 2 (n-1)^2 triangles over 2 km; the
// shot: an ORBIT of radius 40 m at 15 m above a walking subject's base, focus and aperture asked to keep
// the subject sharp and the background blurred by 12 px.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/json.h"
#include "optimizer/optimizer.h"
#include "scene/scene_mesh.h"
#include "shots/planner.h"
#include "shots/shot_list.h"

namespace {

using namespace cinepath;

double TerrainUpM(double e, double n) {
  return 6 * std::sin(e / 97.0) * std::cos(n / 131.0) + 2.5 * std::sin((e + n) / 41.0) + 0.8 * std::cos(e / 13.0);
}

scene::SceneMesh Terrain(size_t faces) {
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

Trajectory Shot() {
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

}  // namespace

int main(int argc, char** argv) {
  size_t faces = 1'000'000;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--faces")) faces = std::stoul(argv[i + 1]);
  }
  const Trajectory plan = Shot();
  const auto build_start = std::chrono::steady_clock::now();
  const scene::SceneMesh terrain = Terrain(faces);
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
  std::printf("plan: %zu samples; terrain: %zu faces (generated in %.2f s, not counted)\n\n", plan.samples.size(),
              terrain.num_faces(), build_s);
  std::printf(
      "| quality | mesh | wall (s) | faces indexed | cost before | cost after | feasible after | "
      "min clearance after (m) | iterations |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const auto quality : {optimizer::OptimizeQuality::kDraft, optimizer::OptimizeQuality::kStandard,
                             optimizer::OptimizeQuality::kFinal}) {
    for (const bool with_mesh : {false, true}) {
      optimizer::OptimizeInput in;
      in.plan = plan;
      in.plan_source = "bench_plan.json";
      in.mesh = with_mesh ? &terrain : nullptr;
      in.scene_source = "terrain";
      const auto start = std::chrono::steady_clock::now();
      const auto r = optimizer::OptimizePlan(in, optimizer::OptimizeOptions::ForQuality(quality));
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const Json& rep = r.report;
      std::printf("| %s | %s | %.3f | %s | %.4g | %.4g | %s | %s | %d |\n", optimizer::OptimizeQualityName(quality),
                  with_mesh ? "1 M faces" : "none", s,
                  with_mesh ? std::to_string(rep["clearance"]["faces_indexed"].get<size_t>()).c_str() : "-",
                  rep["total"]["before"].get<double>(), rep["total"]["after"].get<double>(),
                  rep["feasible_after"].get<bool>() ? "yes" : "no",
                  with_mesh && !rep["clearance"]["min_after_m"].is_null()
                      ? std::to_string(rep["clearance"]["min_after_m"].get<double>()).c_str()
                      : "-",
                  rep["solver"]["iterations"].get<int>());
    }
  }
  return 0;
}
