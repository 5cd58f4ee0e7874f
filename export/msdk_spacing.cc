#include "export/msdk_spacing.h"

#include <fmt/format.h>

namespace cinepath::exporter {

Mission MergeCloseWaypoints(const Mission& mission, double min_spacing_m, std::vector<std::string>& notes) {
  const auto& wps = mission.waypoints;
  if (wps.size() < 2) return mission;
  std::vector<MissionWaypoint> kept = {wps.front()};
  std::vector<double> depart_s = {wps.front().time_s};  // when each kept waypoint is left
  for (size_t w = 1; w < wps.size(); ++w) {
    MissionWaypoint& back = kept.back();
    if ((wps[w].position_enu_m - back.position_enu_m).norm() >= min_spacing_m) {
      kept.push_back(wps[w]);
      depart_s.push_back(wps[w].time_s);
      continue;
    }
    back.record_stop = back.record_stop || wps[w].record_stop;
    back.transit_after = wps[w].transit_after;
    if (wps[w].record_start && !back.record_start) back.record_start = true;
    depart_s.back() = wps[w].time_s;
    back.hold_s = depart_s.back() - back.time_s;
    back.speed_mps = wps[w].speed_mps;
  }
  const size_t merged = wps.size() - kept.size();
  if (merged == 0) return mission;
  for (size_t w = 0; w + 1 < kept.size(); ++w) {
    if (kept[w].transit_after) continue;
    const double length_m = (kept[w + 1].position_enu_m - kept[w].position_enu_m).norm();
    kept[w].speed_mps = length_m / (kept[w + 1].time_s - depart_s[w]);
  }
  if (kept.size() >= 2 && !kept[kept.size() - 2].transit_after) kept.back().speed_mps = kept[kept.size() - 2].speed_mps;
  Mission out = mission;
  out.waypoints = std::move(kept);
  notes.push_back(fmt::format(
      "{} waypoint(s) closer than {:g} m to the previous one merged into it (MSDK v4 minimum spacing), holding "
      "there until the merged waypoint's time; heading and gimbal changes while holding are not carried",
      merged, min_spacing_m));
  return out;
}

}  // namespace cinepath::exporter
