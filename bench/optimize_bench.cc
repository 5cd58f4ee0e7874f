// `cinepath optimize` on a 60 s shot at 30 fps (1,801 samples) with the lens free and depth-of-field
// goals: the time of each preset without a mesh, and against a 1 M-face terrain (the corridor crop and
// both index builds included), with the final cost, the worst limit and the least clearance.
//   optimize_bench [--faces N]
// The shot and the terrain: bench/optimize_bench_scene.h.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "bench/optimize_bench_scene.h"
#include "core/json.h"
#include "optimizer/optimizer.h"

using namespace cinepath;

int main(int argc, char** argv) {
  size_t faces = 1'000'000;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--faces")) faces = std::stoul(argv[i + 1]);
  }
  const Trajectory plan = bench::SixtySecondShot();
  const auto build_start = std::chrono::steady_clock::now();
  const scene::SceneMesh terrain = bench::Terrain(faces);
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
