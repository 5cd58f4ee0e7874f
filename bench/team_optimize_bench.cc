// `cinepath optimize` for several drones: 4 drones x 60 s at 30 fps (1,801 samples each) filming one
// runner — a CHASE, two ORBITs half a turn apart and a DOLLY beside it — with an edit that cuts between
// them every 10 s, so that the separation and out-of-shot terms are live. Prints the optimize time of
// the team against one drone's (the CHASE alone) for each preset, and the team's conflicts before and
// after. Times are wall seconds (steady_clock) and the process's CPU seconds (std::clock, every thread's): the
// solver evaluates its blocks on every core (optimizer/banded_solver.h), so on an idle machine the wall time is
// the shorter; on a busy one the CPU seconds stay meaningful.
//   team_optimize_bench [--drones N]   (N = 1..4, default 4)
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>

#include "core/heap_pages.h"
#include "core/json.h"
#include "optimizer/optimizer.h"
#include "optimizer/team_optimizer.h"
#include "shots/shot_list.h"
#include "shots/team_planner.h"

using namespace cinepath;

namespace {

std::string TeamShots(int drones) {
  const char* all_drones[] = {R"({"name": "chase"})", R"({"name": "orbit-n"})", R"({"name": "orbit-s"})",
                              R"({"name": "dolly"})"};
  const char* all_shots[] = {
      R"({"name": "c", "drone": "chase", "type": "CHASE", "subject": "runner", "duration_s": 60, "distance_m": 12,
          "height_m": 6, "lens": {"frame_height_fraction": 0.3}})",
      R"({"name": "on", "drone": "orbit-n", "type": "ORBIT", "subject": "runner", "duration_s": 60, "radius_m": 18,
          "height_m": 8, "turns": 1, "start_bearing_deg": 0, "lens": {"focal_length_mm": 35}})",
      R"({"name": "os", "drone": "orbit-s", "type": "ORBIT", "subject": "runner", "duration_s": 60, "radius_m": 18,
          "height_m": 8, "turns": 1, "start_bearing_deg": 180, "lens": {"focal_length_mm": 35}})",
      R"({"name": "d", "drone": "dolly", "type": "DOLLY", "subject": "runner", "duration_s": 60, "distance_m": 14,
          "side": "right", "height_m": 3, "lens": {"focal_length_mm": 50}})"};
  const char* names[] = {"chase", "orbit-n", "orbit-s", "dolly"};
  std::string d, s, edit;
  for (int i = 0; i < drones; ++i) {
    d += std::string(i ? ", " : "") + all_drones[i];
    s += std::string(i ? ", " : "") + all_shots[i];
  }
  for (int cut = 0; cut < 6 && drones > 1; ++cut) {
    edit += std::string(cut ? ", " : "") + R"({"at_s": )" + std::to_string(10 * cut) + R"(, "drone": ")" +
            names[cut % drones] + "\"}";
  }
  return R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30,
    "camera": {"filmback": "super35", "width_px": 3840, "height_px": 2160, "min_focal_length_mm": 24,
               "max_focal_length_mm": 120, "min_f_number": 2.8, "max_f_number": 16},
    "drone": "px4-multirotor", "drones": [)" +
         d + R"(],
    "actors": [{"name": "runner", "height_m": 1.8, "interpolation": "catmull_rom", "keyframes": [
      {"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 20, "position_enu_m": [60, 20, 0]},
      {"time_s": 40, "position_enu_m": [100, 80, 0]}, {"time_s": 60, "position_enu_m": [160, 100, 0]}]}],
    "shots": [)" +
         s + "]" + (edit.empty() ? "" : R"(, "edit": [)" + edit + "]") + "}";
}

size_t Count(const std::vector<TeamConflict>& conflicts, const char* limit) {
  size_t n = 0;
  for (const auto& c : conflicts) n += c.limit == limit;
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  PrepareHeapForLargeBuffers(kCommandHeapReserveBytes);  // as `cinepath optimize` does
  int drones = 4;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--drones")) drones = std::stoi(argv[i + 1]);
  }
  if (drones < 1 || drones > 4) return 2;
  const TeamPlan team = shots::PlanTeam(shots::ParseShotList(Json::parse(TeamShots(drones)), "bench_shots.json"));
  std::printf("%d drones x %zu samples; conflicts as planned: %zu separation, %zu in_shot\n\n", drones,
              team.flights[0].plan.samples.size(), Count(team.team.conflicts, "separation"),
              Count(team.team.conflicts, "in_shot"));
  std::printf(
      "| quality | one drone (wall s / CPU s) | team (wall s / CPU s) | team / one (wall) | separation after | in_shot "
      "after | feasible flights |\n|---|---|---|---|---|---|---|\n");
  for (const auto quality : {Quality::kDraft, Quality::kStandard}) {
    const auto options = optimizer::OptimizeOptions::ForQuality(quality);
    optimizer::OptimizeInput one;
    one.plan = team.flights[0].plan;
    const auto wall_since = [](std::chrono::steady_clock::time_point t) {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    };
    std::clock_t start = std::clock();
    auto wall_start = std::chrono::steady_clock::now();
    optimizer::OptimizePlan(one, options);
    const double one_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    const double one_wall_s = wall_since(wall_start);

    optimizer::TeamOptimizeInput in;
    in.plan = team;
    start = std::clock();
    wall_start = std::chrono::steady_clock::now();
    const auto r = optimizer::OptimizeTeam(in, options);
    const double team_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    const double team_wall_s = wall_since(wall_start);
    int feasible = 0;
    for (const auto& f : r.plan.flights) feasible += f.plan.feasibility.feasible();
    std::printf("| %s | %.3f / %.2f | %.3f / %.2f | %.1f | %zu | %zu | %d / %d |\n", QualityName(quality), one_wall_s,
                one_s, team_wall_s, team_s, team_wall_s / one_wall_s, Count(r.plan.team.conflicts, "separation"),
                Count(r.plan.team.conflicts, "in_shot"), feasible, drones);
  }
  return 0;
}
