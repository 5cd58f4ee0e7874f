#include "export/mission_builder.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/angles.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/geoid.h"
#include "core/json.h"
#include "core/local_level.h"
#include "export/dji_turns.h"
#include "export/roi.h"

namespace cinepath::exporter {

namespace {

double ParseNumber(const std::string& token, const std::string& option) {
  double value = 0;
  const char* begin = token.data();
  const char* end = token.data() + token.size();
  while (begin < end && *begin == ' ') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) {
    throw InputError(Located(option, "'" + token + "' is not a number"));
  }
  return value;
}

void RequireFinite(double value, const std::string& plan, size_t index, const char* field) {
  if (!std::isfinite(value)) {
    throw InputError(Located(plan, "samples[" + std::to_string(index) + "]." + field + ": not a finite number"));
  }
}

// Latitude, longitude and the three altitudes of a local ENU point (a waypoint or a point of
// interest: both carry the same fields).
template <typename Located>
void SetGeoPosition(const EnuFrame& frame, const Egm96Geoid& geoid, double home_amsl_m, const Eigen::Vector3d& enu_m,
                    Located* out) {
  const Geodetic g = frame.GeodeticFromEnu(enu_m);
  out->lat_deg = g.lat_deg;
  out->lon_deg = g.lon_deg;
  out->ellipsoidal_height_m = g.height_m;
  out->amsl_m = geoid.AmslFromEllipsoidalM(g.lat_deg, g.lon_deg, g.height_m);
  out->relative_alt_m = out->amsl_m - home_amsl_m;
}

}  // namespace

HomeSpec ParseHomeSpec(const std::string& text, const std::string& option) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) parts.push_back(part);
  if (parts.size() != 3) throw InputError(Located(option, "expected LAT,LON,ALT, got '" + text + "'"));
  HomeSpec home{ParseNumber(parts[0], option), ParseNumber(parts[1], option), ParseNumber(parts[2], option)};
  if (home.lat_deg < -90 || home.lat_deg > 90) throw InputError(Located(option, "latitude outside [-90, 90]"));
  if (home.lon_deg < -180 || home.lon_deg > 180) throw InputError(Located(option, "longitude outside [-180, 180]"));
  return home;
}

namespace {

// Every sample finite, times increasing; InputError naming the plan, the sample and the field.
void CheckSamples(const std::vector<TrajectorySample>& samples, const std::string& plan) {
  if (samples.empty()) throw InputError(Located(plan, "samples: the plan has no samples"));
  for (size_t i = 0; i < samples.size(); ++i) {
    const TrajectorySample& s = samples[i];
    RequireFinite(s.time_s, plan, i, "time_s");
    for (int c = 0; c < 3; ++c) RequireFinite(s.position_enu_m[c], plan, i, "position_enu_m");
    RequireFinite(s.drone_heading_deg, plan, i, "drone_heading_deg");
    RequireFinite(s.gimbal_pitch_deg, plan, i, "gimbal_pitch_deg");
    RequireFinite(s.gimbal_yaw_deg, plan, i, "gimbal_yaw_deg");
    RequireFinite(s.focal_length_mm, plan, i, "focal_length_mm");
    RequireFinite(s.f_number, plan, i, "f_number");
    if (std::isnan(s.focus_distance_m)) RequireFinite(s.focus_distance_m, plan, i, "focus_distance_m");
    if (i > 0 && !(s.time_s > samples[i - 1].time_s)) {
      throw InputError(Located(plan, "samples[" + std::to_string(i) + "].time_s: times must increase"));
    }
  }
}

// The mission's WGS84 origin (the plan's, else the scene's, else home's) and its home (--home, else the
// origin); InputError when neither places the plan.
Geodetic PlaceMission(const Trajectory& trajectory, const MissionBuildOptions& options, const Egm96Geoid& geoid,
                      Mission& mission) {
  const std::string& plan = options.plan_name;
  std::optional<Geodetic> origin = trajectory.origin ? trajectory.origin : options.scene_origin;
  if (!origin) {
    if (options.absolute_altitudes) {
      throw InputError(Located(plan,
                               "origin: the plan has no WGS84 origin (none in the plan, no `scene_origin`); "
                               "absolute altitudes (amsl/ellipsoid) need one"));
    }
    if (!options.home) {
      throw InputError(Located(plan,
                               "origin: the plan has no WGS84 origin; pass `scene_origin` (a scene.json), or "
                               "`home` (LAT,LON,ALT) to place the scene origin at home"));
    }
    origin = Geodetic{options.home->lat_deg, options.home->lon_deg,
                      geoid.EllipsoidalFromAmslM(options.home->lat_deg, options.home->lon_deg, options.home->amsl_m)};
  }
  ValidateGeodetic(*origin, "origin");
  mission.origin = *origin;
  if (options.home) {
    mission.home.lat_deg = options.home->lat_deg;
    mission.home.lon_deg = options.home->lon_deg;
    mission.home.amsl_m = options.home->amsl_m;
    mission.home.ellipsoidal_height_m =
        geoid.EllipsoidalFromAmslM(options.home->lat_deg, options.home->lon_deg, options.home->amsl_m);
  } else {
    mission.home.lat_deg = origin->lat_deg;
    mission.home.lon_deg = origin->lon_deg;
    mission.home.ellipsoidal_height_m = origin->height_m;
    mission.home.amsl_m = geoid.AmslFromEllipsoidalM(origin->lat_deg, origin->lon_deg, origin->height_m);
  }
  return *origin;
}

// The limits the platform checks read: the lens's range, the drone's fence and speed, home's height.
void SetPlatformLimits(const Trajectory& trajectory, const MissionBuildOptions& options, const Geodetic& origin,
                       Mission& mission) {
  const auto& samples = trajectory.samples;
  const CameraSpec& camera = trajectory.camera;
  mission.min_focal_length_mm = camera.min_focal_length_mm;
  mission.max_focal_length_mm = camera.max_focal_length_mm;
  mission.sensor_diagonal_mm = std::hypot(camera.sensor_width_mm, camera.sensor_height_mm);
  mission.plan_sample_count = static_cast<int>(samples.size());
  const DroneProfile& drone = options.drone ? *options.drone : trajectory.drone;
  mission.home_up_m =
      EnuFrame(origin)
          .EnuFromGeodetic(Geodetic{mission.home.lat_deg, mission.home.lon_deg, mission.home.ellipsoidal_height_m})
          .z();
  mission.fence_min_up_m = drone.min_altitude_m;
  mission.fence_max_up_m = drone.max_altitude_m;
  mission.plan_max_horizontal_speed_mps = drone.max_horizontal_speed_m_s;
  mission.plan_drone_name = drone.name;
}

// Continuous runs of samples, [first, last], split where a shot with transition "cut" begins.
std::vector<std::pair<int, int>> CutRuns(const Trajectory& trajectory) {
  const auto& samples = trajectory.samples;
  std::vector<std::pair<int, int>> runs;  // [first, last] sample indices
  int run_start = 0;
  for (size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].shot == samples[i - 1].shot) continue;
    bool cut = false;
    for (const ShotSpan& shot : trajectory.shots) cut |= shot.name == samples[i].shot && shot.transition == "cut";
    if (!cut) continue;
    runs.emplace_back(run_start, static_cast<int>(i) - 1);
    run_start = static_cast<int>(i);
  }
  runs.emplace_back(run_start, static_cast<int>(samples.size()) - 1);
  return runs;
}

// The selection options of one run: its points of interest detected where the target tracks them.
SelectionOptions RunSelectionOptions(const std::vector<TrajectorySample>& run, const MissionBuildOptions& options,
                                     const EnuFrame& frame) {
  SelectionOptions selection_options = options.selection;
  selection_options.rois.clear();
  if (selection_options.roi_tracking != RoiTracking::kNone) {
    selection_options.rois =
        DetectRoiStretches(run, RoiOptions{selection_options.max_angle_deg, options.roi_min_duration_s});
  }
  if (selection_options.roi_tracking == RoiTracking::kHeading) {
    // The target turns its nose to the point: only where the plan's nose already points at it (a
    // gimbal panned off the nose would be turned away).
    std::erase_if(selection_options.rois, [&](const RoiStretch& r) {
      for (int k = r.first_sample; k <= r.last_sample; ++k) {
        // The point's bearing against true north where the drone is, as its heading (core/local_level.h).
        const Eigen::Vector3d to =
            frame.LocalLevelFromEnu(run[k].position_enu_m) * (r.point_enu_m - run[k].position_enu_m);
        if (to.head<2>().norm() < 1e-6) return true;
        const double bearing = HeadingDegFromEnuYaw(std::atan2(to.y(), to.x()));
        if (std::abs(AngleDiffDeg(bearing, run[k].drone_heading_deg)) > selection_options.max_angle_deg) return true;
      }
      return false;
    });
  }
  return selection_options;
}

// The waypoints chosen in every run (sample indices into the whole plan) with their record and transit
// marks and turn damping, and the points of interest; the deviations reached go into `mission`.
struct SelectedWaypoints {
  std::vector<int> idx;
  std::vector<bool> starts, stops, transits;
  std::vector<double> damping;
  std::vector<RoiStretch> roi_stretches;
};

SelectedWaypoints SelectRunWaypoints(const std::vector<TrajectorySample>& samples,
                                     const std::vector<std::pair<int, int>>& runs, const MissionBuildOptions& options,
                                     const EnuFrame& frame, Mission& mission) {
  SelectedWaypoints out;
  for (const auto& [first, last] : runs) {
    const std::vector<TrajectorySample> run(samples.begin() + first, samples.begin() + last + 1);
    const SelectionOptions selection_options = RunSelectionOptions(run, options, frame);
    const Selection selection = SelectWaypoints(run, selection_options);
    double deviation_m = selection.max_deviation_m;
    mission.straight_deviation_reached_m = std::max(mission.straight_deviation_reached_m, deviation_m);
    std::vector<double> run_damping(selection.sample_indices.size(), 0.0);
    if (options.turn_model == TurnModel::kDjiCoordinatedTurn) {
      std::vector<bool> must_stop(selection.sample_indices.size(), false);
      must_stop.front() = must_stop.back() = true;
      for (size_t k = 1; k < selection.sample_indices.size(); ++k) {
        const TrajectorySample& a = run[selection.sample_indices[k - 1]];
        const TrajectorySample& b = run[selection.sample_indices[k]];
        const double speed = (b.position_enu_m - a.position_enu_m).norm() / (b.time_s - a.time_s);
        if (speed < options.min_turn_speed_mps) must_stop[k] = true;
      }
      const TurnFit fit =
          FitCoordinatedTurns(run, selection.sample_indices, must_stop, options.selection.max_deviation_m);
      run_damping = fit.damping_m;
      deviation_m = std::max(deviation_m, fit.max_deviation_m);
    }
    mission.max_deviation_reached_m = std::max(mission.max_deviation_reached_m, deviation_m);
    double angle_deg = selection.max_angle_error_deg;
    for (const RoiStretch& r : selection_options.rois) {
      angle_deg = std::max(angle_deg, r.max_angle_deg);
      RoiStretch global = r;
      global.first_sample += first;
      global.last_sample += first;
      out.roi_stretches.push_back(global);
    }
    mission.max_angle_error_reached_deg = std::max(mission.max_angle_error_reached_deg, angle_deg);
    for (size_t k = 0; k < selection.sample_indices.size(); ++k) {
      out.idx.push_back(first + selection.sample_indices[k]);
      out.starts.push_back(k == 0);
      out.stops.push_back(k + 1 == selection.sample_indices.size());
      out.transits.push_back(k + 1 == selection.sample_indices.size() && last + 1 < static_cast<int>(samples.size()));
      out.damping.push_back(run_damping[k]);
    }
  }
  return out;
}

// A plan without an origin measures its angles against its frame's axes; placed by the mission's origin,
// each sample's are taken against true north and the local vertical where it flies (core/local_level.h),
// a nose off the camera keeping its gimbal yaw.
std::vector<TrajectorySample> AnglesWhereFlown(std::vector<TrajectorySample> samples, const EnuFrame& frame) {
  for (TrajectorySample& s : samples) {
    const double camera_heading_deg =
        LocalGimbalAngles(&frame, s.position_enu_m, s.world_from_camera).drone_heading_deg;
    SetLocalAngles(&frame, s,
                   s.gimbal_yaw_deg == 0 ? std::numeric_limits<double>::quiet_NaN()
                                         : NormalizeDeg360(camera_heading_deg - s.gimbal_yaw_deg));
  }
  return samples;
}

// One MissionWaypoint per selected sample, georeferenced.
void AddWaypoints(const std::vector<TrajectorySample>& samples, const SelectedWaypoints& selected,
                  const EnuFrame& frame, const Egm96Geoid& geoid, Mission& mission) {
  const std::vector<int>& idx = selected.idx;
  for (size_t w = 0; w < idx.size(); ++w) {
    const TrajectorySample& s = samples[idx[w]];
    MissionWaypoint wp;
    wp.sample_index = idx[w];
    wp.time_s = s.time_s;
    wp.position_enu_m = s.position_enu_m;
    SetGeoPosition(frame, geoid, mission.home.amsl_m, s.position_enu_m, &wp);
    wp.heading_deg = s.drone_heading_deg;
    wp.gimbal_pitch_deg = s.gimbal_pitch_deg;
    wp.gimbal_yaw_deg = s.gimbal_yaw_deg;
    wp.focal_length_mm = s.focal_length_mm;
    wp.focus_distance_m = s.focus_distance_m;
    wp.f_number = s.f_number;
    wp.record_start = selected.starts[w];
    wp.record_stop = selected.stops[w];
    wp.transit_after = selected.transits[w];
    wp.turn_damping_m = selected.damping[w];
    mission.waypoints.push_back(wp);
  }
}

// Points of interest: georeferenced, and tied to the waypoints at their ends.
void AddRois(const std::vector<TrajectorySample>& samples, const SelectedWaypoints& selected, const EnuFrame& frame,
             const Egm96Geoid& geoid, Mission& mission) {
  const std::vector<int>& idx = selected.idx;
  for (const RoiStretch& r : selected.roi_stretches) {
    MissionRoi roi;
    roi.first_waypoint = static_cast<int>(std::find(idx.begin(), idx.end(), r.first_sample) - idx.begin());
    roi.last_waypoint = static_cast<int>(std::find(idx.begin(), idx.end(), r.last_sample) - idx.begin());
    CINEPATH_CHECK(roi.first_waypoint < roi.last_waypoint && roi.last_waypoint < static_cast<int>(idx.size()));
    roi.start_time_s = samples[r.first_sample].time_s;
    roi.end_time_s = samples[r.last_sample].time_s;
    roi.point_enu_m = r.point_enu_m;
    SetGeoPosition(frame, geoid, mission.home.amsl_m, r.point_enu_m, &roi);
    roi.fit_angle_deg = r.max_angle_deg;
    for (int w = roi.first_waypoint; w <= roi.last_waypoint; ++w) {
      mission.waypoints[w].roi = static_cast<int>(mission.rois.size());
    }
    mission.rois.push_back(roi);
  }
}

// Speed of the leg leaving each waypoint; the last keeps the previous leg's speed.
void SetLegSpeeds(const MissionBuildOptions& options, Mission& mission) {
  auto& wps = mission.waypoints;
  for (size_t w = 0; w + 1 < wps.size(); ++w) {
    const double length_m = (wps[w + 1].position_enu_m - wps[w].position_enu_m).norm();
    wps[w].speed_mps =
        wps[w].transit_after ? options.transit_speed_mps : length_m / (wps[w + 1].time_s - wps[w].time_s);
  }
  if (wps.size() >= 2) wps.back().speed_mps = wps[wps.size() - 2].speed_mps;
}

}  // namespace

Mission BuildMission(const Trajectory& trajectory, const MissionBuildOptions& options) {
  CheckSamples(trajectory.samples, options.plan_name);
  const Egm96Geoid& geoid = Egm96Geoid::Default();
  Mission mission;
  const Geodetic origin = PlaceMission(trajectory, options, geoid, mission);
  SetPlatformLimits(trajectory, options, origin, mission);
  const EnuFrame frame(origin);
  const std::vector<TrajectorySample> located =
      trajectory.origin ? std::vector<TrajectorySample>() : AnglesWhereFlown(trajectory.samples, frame);
  const std::vector<TrajectorySample>& samples = trajectory.origin ? trajectory.samples : located;
  const std::vector<std::pair<int, int>> runs = CutRuns(trajectory);
  const SelectedWaypoints selected = SelectRunWaypoints(samples, runs, options, frame, mission);
  mission.turn_model = options.turn_model;
  mission.roi_tracking = options.selection.roi_tracking;
  mission.cut_count = static_cast<int>(runs.size()) - 1;
  mission.transit_speed_mps = options.transit_speed_mps;
  AddWaypoints(samples, selected, frame, geoid, mission);
  AddRois(samples, selected, frame, geoid, mission);
  SetLegSpeeds(options, mission);
  return mission;
}

}  // namespace cinepath::exporter
