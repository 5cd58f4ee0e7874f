// `cinepath export` figures for bench/RESULTS.md: the waypoint-count / deviation trade curve of the
// waypoint selection on a 60 s, 30 fps plan, and the time to export it to every format.
//
//   export_bench [--repeats N]
//
// The plan: a figure-eight (lemniscate of Bernoulli, half-width 60 m) flown once in 60 s (≈ 8 m/s),
// climbing and descending 10 m, nose along the path, gimbal tilted at a point 30 m ahead on the
// ground, zooming 24→70→24 mm and pulling focus — every datum a mission carries changes all the time.
// Also: the DJI coordinated-turn model against straight legs on that plan (dji_turns.h), and the
// waypoint counts with and without points of interest (roi.h) on a 60 s ORBIT and a 60 s FLYBY.
// Prints one JSON document.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "core/angles.h"
#include "core/json.h"
#include "export/dji_turns.h"
#include "export/exporter.h"
#include "export/formats.h"
#include "export/mission_builder.h"
#include "export/waypoint_selection.h"

namespace {

using namespace cinepath;

Trajectory FigureEight() {
  Trajectory t;
  t.origin = Geodetic{47.3977419, 8.545594, 535.3};
  t.frame_rate_hz = 30;
  t.camera.min_focal_length_mm = 24;
  t.camera.max_focal_length_mm = 70;
  t.drone.max_horizontal_speed_m_s = 15;
  t.shots.push_back(ShotSpan{"eight", "CUSTOM", 0, 60, "", "continuous", {}});
  const EnuFrame frame(*t.origin);
  const double a = 60, duration = 60;
  const int n = static_cast<int>(duration * t.frame_rate_hz) + 1;
  auto position = [&](double time) {
    const double u = 2 * kPi * time / duration;
    const double d = 1 + std::sin(u) * std::sin(u);
    return Eigen::Vector3d(a * std::cos(u) / d, a * std::sin(u) * std::cos(u) / d, 30 + 10 * std::sin(u));
  };
  for (int i = 0; i < n; ++i) {
    const double time = i / t.frame_rate_hz;
    TrajectorySample s;
    s.time_s = time;
    s.position_enu_m = position(time);
    s.geodetic = frame.GeodeticFromEnu(s.position_enu_m);
    const Eigen::Vector3d v = position(time + 1e-3) - position(time - 1e-3);
    s.drone_heading_deg = HeadingDegFromEnuYaw(std::atan2(v.y(), v.x()));
    s.gimbal_pitch_deg = -DegFromRad(std::atan2(s.position_enu_m.z(), 30.0));
    s.focal_length_mm = 47 - 23 * std::cos(2 * kPi * time / duration);
    s.focus_distance_m = std::hypot(30.0, s.position_enu_m.z());
    s.f_number = 4;
    s.shot = "eight";
    t.samples.push_back(s);
  }
  return t;
}

// Camera on the drone at `p` looking at `target` (world_from_camera, heading, pitch filled).
TrajectorySample LookingAt(double time, const Eigen::Vector3d& p, const Eigen::Vector3d& target) {
  TrajectorySample s;
  s.time_s = time;
  s.position_enu_m = p;
  const Eigen::Vector3d forward = (target - p).normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Matrix3d r;
  r.col(0) = right;
  r.col(1) = forward.cross(right);
  r.col(2) = forward;
  s.world_from_camera = Eigen::Quaterniond(r).normalized();
  s.drone_heading_deg = HeadingDegFromEnuYaw(std::atan2(forward.y(), forward.x()));
  s.gimbal_pitch_deg = DegFromRad(std::asin(forward.z()));
  s.focal_length_mm = 35;
  s.focus_distance_m = (target - p).norm();
  s.f_number = 4;
  s.shot = "shot";
  return s;
}

// 60 s at 30 fps: a full ORBIT (radius 40 m, 30 m up) or a FLYBY (4 m/s, 20 m abeam, from 120 m before to 120 m past)
// about a subject standing at the origin.
Trajectory PoiPlan(bool orbit) {
  Trajectory t;
  t.origin = Geodetic{47.3977419, 8.545594, 535.3};
  t.frame_rate_hz = 30;
  t.shots.push_back(ShotSpan{"shot", orbit ? "ORBIT" : "FLYBY", 0, 60, "subject", "continuous", {}});
  const Eigen::Vector3d subject(0, 0, 1.5);
  for (int i = 0; i <= 1800; ++i) {
    const double time = i / 30.0;
    const double u = 2 * kPi * time / 60;
    const Eigen::Vector3d p =
        orbit ? Eigen::Vector3d(40 * std::cos(u), 40 * std::sin(u), 30) : Eigen::Vector3d(-120 + 4 * time, 20, 15);
    t.samples.push_back(LookingAt(time, p, subject));
  }
  return t;
}

template <typename F>
double MedianSeconds(int repeats, F&& f) {
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(times.begin(), times.end());
  return times[times.size() / 2];
}

// Waypoints against the deviation and angle allowed: the selection's trade curve.
Json TradeCurve(const Trajectory& plan, int repeats) {
  Json curve = Json::array();
  for (double angle : {3.0, 180.0}) {
    for (double e : {0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0}) {
      exporter::Selection sel;
      const double seconds = MedianSeconds(repeats, [&] {
        sel = exporter::SelectWaypoints(plan.samples, {e, angle, exporter::RoiTracking::kNone, {}});
      });
      curve.push_back(Json{{"max_deviation_m", e},
                           {"max_angle_deg", angle},
                           {"waypoints", sel.sample_indices.size()},
                           {"deviation_reached_m", RoundToDecimals(sel.max_deviation_m, 4)},
                           {"angle_error_reached_deg", RoundToDecimals(sel.max_angle_error_deg, 3)},
                           {"selection_ms", RoundToDecimals(seconds * 1e3, 3)}});
    }
  }
  return curve;
}

// DJI WPML: the path flown with coordinated turns (modelled) against the same waypoints as straight
// legs, and what cutting every corner at the largest allowed damping (0.45 × the shorter leg) would
// deviate — the error a straight-leg report hides when the aircraft curves.
Json DjiTurns(const Trajectory& plan, int repeats) {
  Json turns = Json::array();
  for (double e : {0.1, 0.5, 2.0}) {
    exporter::MissionBuildOptions b;
    b.selection = {e, 3.0, exporter::RoiTracking::kNone, {}};
    b.turn_model = exporter::TurnModel::kDjiCoordinatedTurn;
    exporter::Mission m;
    const double seconds = MedianSeconds(repeats, [&] { m = exporter::BuildMission(plan, b); });
    int turning = 0;
    double damping_sum = 0;
    std::vector<int> idx;
    std::vector<double> greedy;
    for (size_t w = 0; w < m.waypoints.size(); ++w) {
      idx.push_back(m.waypoints[w].sample_index);
      turning += m.waypoints[w].turn_damping_m > 0;
      damping_sum += m.waypoints[w].turn_damping_m;
      double d = 0;
      if (w > 0 && w + 1 < m.waypoints.size()) {
        d = 0.45 * std::min((m.waypoints[w].position_enu_m - m.waypoints[w - 1].position_enu_m).norm(),
                            (m.waypoints[w + 1].position_enu_m - m.waypoints[w].position_enu_m).norm());
      }
      greedy.push_back(d);
    }
    turns.push_back(Json{{"max_deviation_m", e},
                         {"waypoints", m.waypoints.size()},
                         {"straight_leg_deviation_m", RoundToDecimals(m.straight_deviation_reached_m, 4)},
                         {"coordinated_turn_deviation_m", RoundToDecimals(m.max_deviation_reached_m, 4)},
                         {"turning_waypoints", turning},
                         {"mean_damping_m", RoundToDecimals(turning ? damping_sum / turning : 0.0, 3)},
                         {"unconstrained_damping_deviation_m",
                          RoundToDecimals(exporter::TurnPathDeviation(plan.samples, idx, greedy), 4)},
                         {"build_ms", RoundToDecimals(seconds * 1e3, 3)}});
  }
  return turns;
}

// Points of interest: waypoints with and without them, per flight model, at 0.5 m / 3 deg.
Json PointsOfInterest(int repeats) {
  Json poi = Json::array();
  for (bool orbit : {true, false}) {
    const Trajectory t = PoiPlan(orbit);
    for (auto tracking :
         {exporter::RoiTracking::kNone, exporter::RoiTracking::kCamera, exporter::RoiTracking::kHeading}) {
      exporter::MissionBuildOptions b;
      b.selection = {0.5, 3.0, tracking, {}};
      exporter::Mission m;
      const double seconds = MedianSeconds(repeats, [&] { m = exporter::BuildMission(t, b); });
      poi.push_back(Json{{"plan", orbit ? "ORBIT 60 s" : "FLYBY 60 s"},
                         {"roi_tracking", tracking == exporter::RoiTracking::kNone     ? "none (--roi off)"
                                          : tracking == exporter::RoiTracking::kCamera ? "camera (MAVLink, Litchi)"
                                                                                       : "heading (DJI WPML)"},
                         {"waypoints", m.waypoints.size()},
                         {"points_of_interest", m.rois.size()},
                         {"deviation_reached_m", RoundToDecimals(m.max_deviation_reached_m, 4)},
                         {"angle_error_reached_deg", RoundToDecimals(m.max_angle_error_reached_deg, 3)},
                         {"build_ms", RoundToDecimals(seconds * 1e3, 3)}});
    }
  }
  return poi;
}

// Each format's export time, and all six together.
Json ExportTimes(const Trajectory& plan, int repeats) {
  const std::vector<exporter::Format> formats = {exporter::Format::kQgcPlan,     exporter::Format::kQgcWpl,
                                                 exporter::Format::kMavlinkBin,  exporter::Format::kDjiWpml,
                                                 exporter::Format::kDjiMsdkJson, exporter::Format::kLitchiCsv};
  Json timings = Json::array();
  auto time_export = [&](const std::vector<exporter::Format>& fs, const std::string& label) {
    exporter::ExportOptions options;
    options.formats = fs;
    options.force = true;  // MSDK v4's 99-waypoint cap is exceeded at tight tolerances
    options.build.selection = {0.5, 3.0, exporter::RoiTracking::kNone, {}};
    size_t bytes = 0, waypoints = 0;
    const double seconds = MedianSeconds(repeats, [&] {
      const exporter::ExportResult r = exporter::ExportMission(plan, options);
      bytes = 0;
      for (const auto& f : r.files) bytes += f.contents.size();
      waypoints = r.mission.waypoints.size();
    });
    timings.push_back(Json{{"formats", label},
                           {"waypoints", waypoints},
                           {"bytes", bytes},
                           {"export_ms", RoundToDecimals(seconds * 1e3, 3)}});
  };
  for (auto f : formats) time_export({f}, exporter::FormatName(f));
  time_export(formats, "all six");
  return timings;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 20;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--repeats") == 0) repeats = std::max(1, std::atoi(argv[i + 1]));
  }
  const Trajectory plan = FigureEight();
  Json out;
  out["plan"] = Json{{"duration_s", 60}, {"frame_rate_hz", 30}, {"samples", plan.samples.size()}};
  out["trade_curve"] = TradeCurve(plan, repeats);
  out["dji_turns_at_3deg"] = DjiTurns(plan, repeats);
  out["points_of_interest_at_0.5m_3deg"] = PointsOfInterest(repeats);
  out["export_time_at_0.5m_3deg"] = ExportTimes(plan, repeats);
  std::fputs(DumpJson(out).c_str(), stdout);
  return 0;
}
