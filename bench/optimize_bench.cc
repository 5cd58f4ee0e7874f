// `cinepath optimize` on a 60 s shot at 30 fps (1,801 samples) with the lens free and depth-of-field
// goals: the time of each preset without a mesh, and against a 1 M-face terrain (the corridor crop and
// both index builds included), with the ladder's objective, the fraction of the change the guard kept,
// the limits the solver's own output broke (the guard's raw_broke), the worst limit still broken, the final
// cost and the least clearance.
//   optimize_bench [--faces N] [--quality draft|standard|final] [--mesh none|terrain] [--solver banded|ceres]
// (`--solver ceres`: Ceres' own Levenberg-Marquardt on the same problem, the peer of the banded solver)
// The shot and the terrain: bench/optimize_bench_scene.h.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>

#include "bench/optimize_bench_scene.h"
#include "core/heap_pages.h"
#include "core/json.h"
#include "optimizer/optimizer.h"

using namespace cinepath;

namespace {
// CPU seconds of every thread of the process (the index builds may use more than one).
double ProcessCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
}  // namespace

int main(int argc, char** argv) {
  PrepareHeapForLargeBuffers(kCommandHeapReserveBytes);  // as `cinepath optimize` does
  size_t faces = 1'000'000;
  std::string only_quality, only_mesh;  // empty: every preset, with and without the terrain
  bool ceres_solver = false;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--faces")) faces = std::stoul(argv[i + 1]);
    if (!std::strcmp(argv[i], "--quality")) only_quality = argv[i + 1];
    if (!std::strcmp(argv[i], "--mesh")) only_mesh = argv[i + 1];
    if (!std::strcmp(argv[i], "--solver")) ceres_solver = !std::strcmp(argv[i + 1], "ceres");
  }
  const Trajectory plan = bench::SixtySecondShot();
  const auto build_start = std::chrono::steady_clock::now();
  const scene::SceneMesh terrain = only_mesh == "none" ? scene::SceneMesh() : bench::Terrain(faces);
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
  std::printf("plan: %zu samples; terrain: %zu faces (generated in %.2f s, not counted)\n\n", plan.samples.size(),
              terrain.num_faces(), build_s);
  std::printf(
      "| quality | mesh | wall (s) | CPU (s) | faces indexed | objective | stages kept | alpha | raw broke | worst "
      "still broken "
      "| cost before | cost after | feasible after | min clearance after (m) | iterations |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto quality : {Quality::kDraft, Quality::kStandard, Quality::kFinal}) {
    if (!only_quality.empty() && only_quality != QualityName(quality)) continue;
    for (const bool with_mesh : {false, true}) {
      if (!only_mesh.empty() && only_mesh != (with_mesh ? "terrain" : "none")) continue;
      optimizer::OptimizeInput in;
      in.plan = plan;
      in.plan_source = "bench_plan.json";
      in.mesh = with_mesh ? &terrain : nullptr;
      in.scene_source = "terrain";
      const auto start = std::chrono::steady_clock::now();
      const double cpu_start = ProcessCpuSeconds();
      optimizer::OptimizeOptions options = optimizer::OptimizeOptions::ForQuality(quality);
      options.ceres_solver = ceres_solver;
      const auto r = optimizer::OptimizePlan(in, options);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double cpu_s = ProcessCpuSeconds() - cpu_start;
      const Json& rep = r.report;
      // The worst limit still broken, relative to its limit (a count for lines of sight and crossings).
      std::string worst = "-", kept, raw_broke;
      for (const auto& limit : rep["guard"]["raw_broke"]) {
        raw_broke += std::string(raw_broke.empty() ? "" : ", ") + limit.get<std::string>();
      }
      if (raw_broke.empty()) raw_broke = "-";
      double worst_ratio = 0;
      for (const auto& v : rep["guard"]["still_broken"]) {
        const double ratio = v["by"].get<double>() / std::max(1.0, std::fabs(v["limit_value"].get<double>()));
        if (ratio <= worst_ratio) continue;
        worst_ratio = ratio;
        worst = v["limit"].get<std::string>() + " " + v["worst"].dump() + " " + v["unit"].get<std::string>() + " (" +
                v["start_time_s"].dump() + "-" + v["end_time_s"].dump() + " s)";
      }
      for (const auto& stage : rep["ladder"]) {
        kept += std::string(kept.empty() ? "" : " ") + (stage["kept"].get<bool>() ? "y" : "n");
      }
      std::printf("| %s | %s | %.3f | %.3f | %s | %.6g | %s | %.4g | %s | %s | %.4g | %.4g | %s | %s | %d |\n",
                  QualityName(quality), with_mesh ? "1 M faces" : "none", s, cpu_s,
                  with_mesh ? std::to_string(rep["clearance"]["faces_indexed"].get<size_t>()).c_str() : "-",
                  rep["objective"].get<double>(), kept.c_str(), rep["guard"]["alpha"].get<double>(), raw_broke.c_str(),
                  worst.c_str(), rep["total"]["before"].get<double>(), rep["total"]["after"].get<double>(),
                  rep["feasible_after"].get<bool>() ? "yes" : "no",
                  with_mesh && !rep["clearance"]["min_after_m"].is_null()
                      ? std::to_string(rep["clearance"]["min_after_m"].get<double>()).c_str()
                      : "-",
                  rep["solver"]["iterations"].get<int>());
    }
  }
  return 0;
}
