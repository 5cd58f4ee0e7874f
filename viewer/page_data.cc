#include "viewer/page_data.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/feasibility.h"
#include "core/three_frame.h"

namespace cinepath::viewer {
namespace {

void AppendVector(Json* array, const Eigen::Vector3d& v, int decimals) {
  for (int a = 0; a < 3; ++a) array->push_back(RoundToDecimals(v[a], decimals));
}

Json FiniteOrNull(double value, int decimals) {
  return std::isfinite(value) ? Json(RoundToDecimals(value, decimals)) : Json(nullptr);
}

// What every flight's camera is drawn from, per sample: time, position and camera orientation in
// three.js's frame, its lens (focal length, vertical angle of view, f-number, focus: null at infinity),
// so that the camera view through any drone reads that drone's lens.
Json CameraTrackJson(const Trajectory& plan) {
  Json time = Json::array(), position = Json::array(), quaternion = Json::array(), vfov = Json::array();
  Json focus = Json::array(), focal = Json::array(), f_number = Json::array();
  for (const TrajectorySample& s : plan.samples) {
    time.push_back(RoundToDecimals(s.time_s, 6));
    AppendVector(&position, ThreeFromEnu(s.position_enu_m), 3);
    const Eigen::Quaterniond q = ThreeCameraFromWorldFromCamera(s.world_from_camera);
    for (double c : {q.x(), q.y(), q.z(), q.w()}) quaternion.push_back(RoundToDecimals(c, 6));
    vfov.push_back(RoundToDecimals(VerticalFieldOfViewDeg(plan.camera, s.focal_length_mm), 4));
    focus.push_back(FiniteOrNull(s.focus_distance_m, 3));
    focal.push_back(RoundToDecimals(s.focal_length_mm, 3));
    f_number.push_back(RoundToDecimals(s.f_number, 3));
  }
  return {{"time_s", time},           {"position_m", position},    {"quaternion", quaternion},
          {"vertical_fov_deg", vfov}, {"focus_distance_m", focus}, {"focal_length_mm", focal},
          {"f_number", f_number}};
}

// The samples a cut lies before (CutBeforeSamples), by index.
Json CutsJson(const Trajectory& plan) {
  Json cuts = Json::array();
  const std::vector<bool> cut_before = CutBeforeSamples(plan);
  for (size_t k = 0; k < cut_before.size(); ++k) {
    if (cut_before[k]) cuts.push_back(k);
  }
  return cuts;
}

}  // namespace

std::vector<bool> CutBeforeSamples(const Trajectory& plan) {
  const auto& s = plan.samples;
  std::vector<bool> cut(s.size(), false);
  for (size_t k = 1; k < s.size(); ++k) {
    if (s[k].shot == s[k - 1].shot) continue;
    for (const ShotSpan& shot : plan.shots) {
      if (shot.name == s[k].shot && shot.transition == "cut") cut[k] = true;
    }
  }
  return cut;
}

std::vector<double> SampleSpeedsMps(const Trajectory& plan) {
  const auto& s = plan.samples;
  std::vector<double> speeds(s.size(), 0.0);
  if (s.size() < 2) return speeds;
  const std::vector<bool> cut = CutBeforeSamples(plan);
  for (size_t k = 0; k < s.size(); ++k) {
    const size_t a = k == 0 || cut[k] ? k : k - 1;
    const size_t b = k + 1 == s.size() || cut[k + 1] ? k : k + 1;
    const double dt = s[b].time_s - s[a].time_s;
    speeds[k] = dt > 0 ? (s[b].position_enu_m - s[a].position_enu_m).norm() / dt : 0.0;
  }
  return speeds;
}

namespace {

// A flight's shots with their times.
Json ShotsJson(const Trajectory& plan) {
  Json shots = Json::array();
  for (const ShotSpan& shot : plan.shots) {
    shots.push_back({{"name", shot.name},
                     {"type", shot.type},
                     {"subject", shot.subject},
                     {"start_time_s", RoundToDecimals(shot.start_time_s, 6)},
                     {"end_time_s", RoundToDecimals(shot.end_time_s, 6)}});
  }
  return shots;
}

// A flight's keyframes: shot, time and where (three.js frame).
Json KeyframesJson(const Trajectory& plan) {
  Json keyframes = Json::array();
  for (const Keyframe& key : plan.keyframes) {
    Json p = Json::array();
    AppendVector(&p, ThreeFromEnu(key.position_enu_m), 3);
    keyframes.push_back({{"shot", key.shot}, {"time_s", RoundToDecimals(key.time_s, 6)}, {"position_m", p}});
  }
  return keyframes;
}

// A flight's broken limits (its feasibility report's ranges).
Json ViolationsJson(const Trajectory& plan) {
  Json violations = Json::array();
  for (const FeasibilityViolation& v : plan.feasibility.violations) {
    violations.push_back({{"limit", v.limit},
                          {"shot", v.shot},
                          {"start_time_s", RoundToDecimals(v.start_time_s, 6)},
                          {"end_time_s", RoundToDecimals(v.end_time_s, 6)},
                          {"worst_value", RoundToDecimals(v.worst_value, 6)},
                          {"limit_value", RoundToDecimals(v.limit_value, 6)},
                          {"minimum", IsMinimumLimit(v.limit)},
                          {"unit", v.unit}});
  }
  return violations;
}

// The primary flight in detail: what the lens graphs, the timeline, the readout and the feasibility box show.
Json FlightDetailJson(const Trajectory& plan, const std::string& plan_name, const std::optional<Geodetic>& origin) {
  Json data = Json::object();
  data["format"] = "cinepath.previs/1";
  data["plan"] = plan_name;
  if (origin) {
    data["origin"] = {{"lat_deg", RoundToDecimals(origin->lat_deg, 9)},
                      {"lon_deg", RoundToDecimals(origin->lon_deg, 9)},
                      {"height_m", RoundToDecimals(origin->height_m, 3)}};
  } else {
    data["origin"] = nullptr;
  }
  data["frame_rate_hz"] = plan.frame_rate_hz;
  const ImageExtentMm image = plan.camera.image_extent_mm();
  data["camera"] = {{"filmback", plan.camera.filmback},
                    {"sensor_width_mm", plan.camera.sensor_width_mm},
                    {"image_height_mm", RoundToDecimals(image.height_mm, 6)},
                    {"width_px", plan.camera.width_px},
                    {"height_px", plan.camera.height_px}};
  data["drone"] = plan.drone.name;

  Json speed = Json::array(), shot_index = Json::array();
  const std::vector<double> speeds = SampleSpeedsMps(plan);
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    const TrajectorySample& s = plan.samples[k];
    speed.push_back(RoundToDecimals(speeds[k], 3));
    int index = -1;
    for (size_t i = 0; i < plan.shots.size(); ++i) {
      if (plan.shots[i].name == s.shot) index = int(i);
    }
    shot_index.push_back(index);
  }
  data["cuts_before_sample"] = CutsJson(plan);
  Json samples = CameraTrackJson(plan);
  samples["speed_m_s"] = speed;
  samples["shot"] = shot_index;
  data["samples"] = samples;

  data["shots"] = ShotsJson(plan);
  data["keyframes"] = KeyframesJson(plan);
  Json subjects = Json::array();
  for (const SubjectTrack& subject : plan.subjects) {
    Json p = Json::array();
    for (const auto& v : subject.positions_enu_m) AppendVector(&p, ThreeFromEnu(v), 3);
    subjects.push_back({{"name", subject.name}, {"height_m", subject.height_m}, {"position_m", p}});
  }
  data["subjects"] = subjects;
  data["violations"] = ViolationsJson(plan);
  data["skipped_checks"] = plan.feasibility.skipped;
  return data;
}

// One flight's track as every flight is drawn (its path, its camera at each sample, its home): the primary
// flight's samples, shots with their times, keyframes and broken limits are already in the page's
// "samples", "shots", "keyframes" and "violations" (FlightDetailJson), so only the others carry theirs
// ("shot_spans", "keyframes", "violations").
Json FlightJson(const DroneFlight& flight, const char* colour, bool with_samples) {
  const Trajectory& t = flight.plan;
  Json home = nullptr;
  if (flight.home_enu_m) {
    home = Json::array();
    AppendVector(&home, ThreeFromEnu(*flight.home_enu_m), 3);
  }
  Json shots = Json::array();
  for (const ShotSpan& shot : t.shots) shots.push_back(shot.name);
  Json json = {{"name", flight.name},
               {"colour", colour},
               {"drone", t.drone.name},
               {"aspect", double(t.camera.width_px) / double(std::max(1, t.camera.height_px))},
               {"home_m", home},
               {"shots", shots},
               {"cuts_before_sample", CutsJson(t)}};
  if (with_samples) {
    json.update(CameraTrackJson(t));
    json["shot_spans"] = ShotsJson(t);
    json["keyframes"] = KeyframesJson(t);
    json["violations"] = ViolationsJson(t);
  }
  return json;
}

// The edit and the team report's conflicts (both empty for one drone).
Json TeamJson(const TeamPlan& plan, size_t primary) {
  static const char* const kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};
  Json flights = Json::array();
  for (size_t f = 0; f < plan.flights.size(); ++f)
    flights.push_back(FlightJson(plan.flights[f], kPalette[f % 10], f != primary));
  Json edit = Json::array();
  for (const EditCut& cut : plan.edit) {
    edit.push_back({{"at_s", RoundToDecimals(cut.at_s, 6)}, {"drone", cut.drone}, {"match_focus", cut.match_focus}});
  }
  Json conflicts = Json::array();
  for (const TeamConflict& c : plan.team.conflicts) {
    conflicts.push_back({{"limit", c.limit},
                         {"drone", c.drone},
                         {"other", c.other},
                         {"start_time_s", RoundToDecimals(c.start_time_s, 6)},
                         {"end_time_s", RoundToDecimals(c.end_time_s, 6)},
                         {"worst_value", RoundToDecimals(c.worst_value, 6)},
                         {"limit_value", RoundToDecimals(c.limit_value, 6)},
                         {"unit", c.unit}});
  }
  return {{"primary", primary},
          {"flights", flights},
          {"edit", edit},
          {"conflicts", conflicts},
          {"min_separation_m", RoundToDecimals(plan.team.min_separation_m, 6)}};
}

}  // namespace

Json PageDataJson(const TeamPlan& plan, size_t primary, const std::string& plan_name,
                  const std::optional<Geodetic>& origin) {
  CINEPATH_CHECK(primary < plan.flights.size());
  Json data = FlightDetailJson(plan.flights[primary].plan, plan_name, origin);
  data["team"] = TeamJson(plan, primary);
  return data;
}

}  // namespace cinepath::viewer
