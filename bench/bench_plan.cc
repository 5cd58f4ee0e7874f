// Samples per second for a long multi-shot plan: 11 shots (every type), 10 minutes at 30 fps
// (18 001 samples), a moving car and a static subject, with an origin (lat/lon per sample).
//   ninja -C build bench_plan && build/bench/bench_plan
#include <benchmark/benchmark.h>

#include "core/plan_file.h"
#include "shots/planner.h"
#include "shots/shot_list.h"

namespace {

using cinepath::Json;

Json LongShotList() {
  return Json::parse(R"({
    "schema": "cinepath.shots/1",
    "origin": {"lat_deg": 46.84265, "lon_deg": -91.99445, "height_m": 153.0},
    "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "min_focal_length_mm": 18, "max_focal_length_mm": 300},
    "drone": "px4_default_quad",
    "actors": [
      {"name": "hero", "height_m": 1.8, "position_enu_m": [0, 0, 0]},
      {"name": "car", "height_m": 1.5, "interpolation": "cubic_bspline", "keyframes": [
        {"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 200, "position_enu_m": [800, 300, 0]},
        {"time_s": 400, "position_enu_m": [1200, 900, 5]}, {"time_s": 600, "position_enu_m": [1500, 1600, 8]}]}
    ],
    "shots": [
      {"type": "CHASE", "subject": "car", "duration_s": 60, "distance_m": 20, "height_m": 6,
        "lens": {"frame_height_fraction": 0.2}},
      {"type": "FLYBY", "subject": "car", "duration_s": 50, "closest_distance_m": 15, "height_m": 4, "speed_m_s": 1,
        "blend_s": 8},
      {"type": "TRACK", "subject": "car", "duration_s": 60, "distance_m": 12, "blend_s": 8},
      {"type": "ORBIT", "subject": "hero", "duration_s": 60, "radius_m": 40, "height_m": 15, "turns": 1,
        "transition": "cut",
       "lens": {"frame_height_fraction": 0.3, "screen_position": "right_third"}},
      {"type": "HELIX", "subject": "hero", "duration_s": 60, "radius_m": 40, "radius_end_m": 60, "height_m": 15,
        "height_end_m": 60, "turns": 1},
      {"type": "CRANE", "subject": "hero", "duration_s": 50, "distance_m": 30, "height_m": 5, "height_end_m": 40,
        "tilt_start_deg": -60},
      {"type": "DRONIE", "subject": "hero", "duration_s": 50, "distance_m": 30, "distance_end_m": 150,
        "height_m": 40, "height_end_m": 90},
      {"type": "TOP-DOWN", "subject": "hero", "duration_s": 50, "height_m": 60, "rotate_deg": 180},
      {"type": "DOLLY-ZOOM", "subject": "hero", "duration_s": 60, "distance_m": 10, "distance_end_m": 80,
        "height_m": 0.9,
       "transition": "cut", "lens": {"focal_length_mm": 20}},
      {"type": "LOCKED-OFF", "subject": "hero", "duration_s": 50, "bearing_deg": 90, "distance_m": 100,
        "height_m": 20, "pan": true},
      {"type": "KEYFRAMES", "subject": "hero", "interpolation": "catmull_rom", "keys": [
        {"time_s": 0, "position_enu_m": [100, 0, 20]}, {"time_s": 20, "position_enu_m": [60, 60, 30]},
        {"time_s": 35, "position_enu_m": [0, 80, 25]}, {"time_s": 50, "position_enu_m": [-50, 40, 15]}]}
    ]})");
}

void BM_PlanLongMultiShot(benchmark::State& state) {
  const cinepath::shots::ShotList list = cinepath::shots::ParseShotList(LongShotList(), "bench.json");
  size_t samples = 0;
  for (auto _ : state) {
    const cinepath::Trajectory plan = cinepath::shots::PlanShots(list);
    samples = plan.samples.size();
    benchmark::DoNotOptimize(plan.samples.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * samples));
  state.counters["samples"] = static_cast<double>(samples);
}
BENCHMARK(BM_PlanLongMultiShot)->Unit(benchmark::kMillisecond);

void BM_WritePlanJson(benchmark::State& state) {
  const cinepath::Trajectory plan =
      cinepath::shots::PlanShots(cinepath::shots::ParseShotList(LongShotList(), "bench.json"));
  size_t bytes = 0;
  for (auto _ : state) {
    const std::string text = cinepath::PlanToText(plan);
    bytes = text.size();
    benchmark::DoNotOptimize(text.data());
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * plan.samples.size()));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes));
}
BENCHMARK(BM_WritePlanJson)->Unit(benchmark::kMillisecond);

}  // namespace
