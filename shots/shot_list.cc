#include "shots/shot_list.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/angles.h"
#include "core/drone_profiles.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/geodetic_json.h"
#include "core/number_format.h"
#include "core/optics.h"
#include "core/rotation.h"
#include "shots/shot_syntax.h"

namespace cinepath::shots {
namespace {

Geodetic ParseOrigin(const JsonField& f) {
  f.RejectUnknownKeys({"lat_deg", "lon_deg", "height_m"});
  return GeodeticFromJson(f);
}

// Every number in a shot list is 0 or between 1e-6 and 1e7 in magnitude (m, s, deg, mm ...): far
// beyond any real shot on both ends (a micrometre, a microsecond), and so nothing downstream overflows
// (1 / 1e-320 is infinite) or loses every digit.
void RejectOutOfRangeNumbers(const JsonField& f) {
  if (f.IsNumber()) {
    const double v = std::fabs(f.AsDouble());
    if (v > 1e7) f.Fail("must be 0 or between 1e-6 and 1e7 in magnitude");
    if (v != 0 && v < 1e-6) f.Fail("must be 0 or between 1e-6 and 1e7 in magnitude");
  } else if (f.IsObject()) {
    for (const auto& item : f.node().items()) RejectOutOfRangeNumbers(f[item.key()]);
  } else if (f.IsArray()) {
    for (const auto& e : f.Elements()) RejectOutOfRangeNumbers(e);
  }
}

CameraSpec ParseCamera(const JsonField& f) {
  f.RejectUnknownKeys({"filmback", "sensor_width_mm", "sensor_height_mm", "width_px", "height_px",
                       "min_focal_length_mm", "max_focal_length_mm", "min_f_number", "max_f_number",
                       "min_focus_distance_m", "coc_mm", "max_focal_rate_mm_s", "max_focus_rate_m_s",
                       "max_aperture_rate_stops_s"});
  CameraSpec c;
  if (auto fb = f.Find("filmback")) {
    if (f.Has("sensor_width_mm") || f.Has("sensor_height_mm")) {
      f.Fail("give either \"filmback\" or \"sensor_width_mm\"/\"sensor_height_mm\", not both");
    }
    auto preset = FindFilmback(fb->AsString());
    if (!preset) {
      std::string names;
      for (const auto& p : FilmbackPresets()) names += (names.empty() ? "" : ", ") + p.name;
      fb->Fail("unknown filmback \"" + fb->AsString() + "\" (" + names + ")");
    }
    c.filmback = preset->name;
    c.sensor_width_mm = preset->width_mm;
    c.sensor_height_mm = preset->height_mm;
  } else {
    c.filmback = "custom";
    c.sensor_width_mm = f["sensor_width_mm"].AsPositive();
    c.sensor_height_mm = f["sensor_height_mm"].AsPositive();
  }
  auto positive_int = [&](const char* key, int fallback) {
    if (!f.Has(key)) return fallback;
    const int64_t v = f[key].AsInt();
    if (v <= 0 || v > 100000) f[key].Fail("must be in [1, 100000]");
    return static_cast<int>(v);
  };
  c.width_px = positive_int("width_px", 3840);
  c.height_px = positive_int("height_px", 2160);
  c.min_focal_length_mm = f["min_focal_length_mm"].AsPositive();
  c.max_focal_length_mm = f.Has("max_focal_length_mm") ? f["max_focal_length_mm"].AsPositive() : c.min_focal_length_mm;
  if (c.max_focal_length_mm < c.min_focal_length_mm) f["max_focal_length_mm"].Fail("must be >= min_focal_length_mm");
  c.min_f_number = f.Has("min_f_number") ? f["min_f_number"].AsPositive() : 2.8;
  c.max_f_number = f.Has("max_f_number") ? f["max_f_number"].AsPositive() : 16;
  if (c.max_f_number < c.min_f_number) f["max_f_number"].Fail("must be >= min_f_number");
  c.min_focus_distance_m = f.Has("min_focus_distance_m") ? f["min_focus_distance_m"].AsPositive() : 0.5;
  c.coc_mm = f.Has("coc_mm") ? f["coc_mm"].AsPositive() : DefaultCocMm(c.sensor_width_mm, c.sensor_height_mm);
  if (f.Has("max_focal_rate_mm_s")) c.max_focal_rate_mm_s = f["max_focal_rate_mm_s"].AsPositive();
  if (f.Has("max_focus_rate_m_s")) c.max_focus_rate_m_s = f["max_focus_rate_m_s"].AsPositive();
  if (f.Has("max_aperture_rate_stops_s")) c.max_aperture_rate_stops_s = f["max_aperture_rate_stops_s"].AsPositive();
  return c;
}

// "drone": "<profile>" or {"profile": "<profile>", <any DroneProfile field>: value, ...}.
DroneProfile ParseDrone(const JsonField& f) {
  if (f.IsString()) return RequireDroneProfile(f.AsString(), f.Where());
  if (!f.IsObject()) f.Fail("expected a profile name or {\"profile\": ..., overrides}");
  DroneProfile d = RequireDroneProfile(f["profile"].AsString(), f["profile"].Where());
  const std::string name = d.name;
  ApplyDroneProfileJson(f, &d, {"profile"});
  if (!f.Has("name")) d.name = name;
  return d;
}

// A drone with a built-in lens (core/drone_profile.h, FixedLens): the camera's ranges must lie within it.
void CheckCameraAgainstFixedLens(const JsonField& camera_field, const CameraSpec& c, const DroneProfile& drone) {
  if (!drone.lens) return;
  const FixedLens& l = *drone.lens;
  auto outside = [&](const char* key, double v, double lo, double hi, const std::string& what) {
    if (v < lo - 1e-9 || v > hi + 1e-9) {
      camera_field[key].Fail("outside the " + drone.name + "'s built-in lens (" + what + ")");
    }
  };
  const std::string focal = FormatShortest(l.min_focal_length_mm) + "-" + FormatShortest(l.max_focal_length_mm) + " mm";
  const std::string stops = "f/" + FormatShortest(l.min_f_number) + "-" + FormatShortest(l.max_f_number);
  outside("min_focal_length_mm", c.min_focal_length_mm, l.min_focal_length_mm, l.max_focal_length_mm, focal);
  outside("max_focal_length_mm", c.max_focal_length_mm, l.min_focal_length_mm, l.max_focal_length_mm, focal);
  if (camera_field.Has("min_f_number") || camera_field.Has("max_f_number")) {
    outside("min_f_number", c.min_f_number, l.min_f_number, l.max_f_number, stops);
    outside("max_f_number", c.max_f_number, l.min_f_number, l.max_f_number, stops);
  } else {
    camera_field.Fail("the " + drone.name + " has a built-in " + stops +
                      " lens: give min_f_number and max_f_number within it");
  }
}

// "drones": [{"name", "drone" (a profile or overrides), "camera", "home_enu_m" | "home"}]. A drone without
// "drone" or "camera" takes the top-level one.
void ParseDrones(const JsonField& drones, const JsonField& root, const EnuFrame* frame, ShotList& list) {
  if (!drones.IsArray() || drones.size() == 0) drones.Fail("expected a non-empty array of drones");
  for (const auto& f : drones.Elements()) {
    f.RejectUnknownKeys({"name", "drone", "camera", "home_enu_m", "home", "above_ground_m"});
    DroneSpec d;
    d.name = f["name"].AsString();
    if (d.name.empty()) f["name"].Fail("must not be empty");
    if (d.name.find_first_of("/\\") != std::string::npos || d.name == "." || d.name == ".." || d.name == "edit") {
      f["name"].Fail("must be usable as a folder name (no '/', '\\', \".\", \"..\" or \"edit\")");
    }
    if (list.FindDrone(d.name) >= 0) f["name"].Fail("duplicate drone name \"" + d.name + "\"");
    d.drone = f.Has("drone") ? ParseDrone(f["drone"]) : list.drone;
    if (f.Has("camera")) {
      d.camera = ParseCamera(f["camera"]);
      CheckCameraAgainstFixedLens(f["camera"], d.camera, d.drone);
    } else if (root.Has("camera")) {
      d.camera = list.camera;
      CheckCameraAgainstFixedLens(root["camera"], d.camera, d.drone);
    } else {
      f.Fail("missing \"camera\" (give it here or at the top level)");
    }
    if (f.Has("home_enu_m") || f.Has("home")) {
      d.home_enu_m = ParsePosition(f, "home_enu_m", "home", PositionContext{frame, list.ground.get()});
    }
    list.drones.push_back(std::move(d));
  }
}

// "edit": [{"at_s", "drone", "match_focus"}], cuts in increasing time.
void ParseEdit(const JsonField& edit, ShotList& list) {
  if (!edit.IsArray()) edit.Fail("expected an array of cuts");
  for (const auto& f : edit.Elements()) {
    f.RejectUnknownKeys({"at_s", "drone", "match_focus"});
    EditCut cut;
    cut.at_s = f["at_s"].AsNonNegative();
    cut.drone = f["drone"].AsString();
    if (list.FindDrone(cut.drone) < 0) f["drone"].Fail("no drone is named \"" + cut.drone + "\" (see \"drones\")");
    cut.match_focus = f.BoolOr("match_focus", false);
    if (!list.edit.empty() && !(cut.at_s > list.edit.back().at_s)) f["at_s"].Fail("cuts must be in increasing time");
    if (!list.edit.empty() && list.edit.back().drone == cut.drone) {
      f["drone"].Fail("cuts to the drone that is already live");
    }
    if (cut.match_focus && list.edit.empty()) f["match_focus"].Fail("the first cut has no outgoing camera");
    list.edit.push_back(std::move(cut));
  }
}

}  // namespace

int ShotList::FindDrone(const std::string& name) const {
  for (size_t i = 0; i < drones.size(); ++i) {
    if (drones[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int ShotList::FindActor(const std::string& name) const {
  for (size_t i = 0; i < actors.size(); ++i) {
    if (actors[i].name() == name) return static_cast<int>(i);
  }
  return -1;
}

std::optional<Geodetic> ShotListOrigin(const Json& document, const std::string& source) {
  const JsonField root(document, source);
  if (!root.IsObject()) return std::nullopt;  // ParseShotList says what is wrong
  if (auto o = root.Find("origin")) return ParseOrigin(*o);
  return std::nullopt;
}

bool SameOrigin(const Geodetic& a, const Geodetic& b) {
  return std::fabs(a.lat_deg - b.lat_deg) <= 1e-9 && std::fabs(a.lon_deg - b.lon_deg) <= 1e-9 &&
         std::fabs(a.height_m - b.height_m) <= 1e-6;
}

ShotList ParseShotList(const Json& document, const std::string& source, const std::optional<Geodetic>& scene_origin,
                       std::shared_ptr<const Ground> ground) {
  const JsonField root(document, source);
  if (!root.IsObject()) root.Fail("expected a shot list (a JSON object)");
  root.RejectUnknownKeys(
      {"schema", "origin", "frame_rate_hz", "camera", "drone", "drones", "edit", "actors", "shots", "description"});
  const std::string schema = root["schema"].AsString();
  if (schema != kShotsSchema) {
    root["schema"].Fail("unsupported shot-list version \"" + schema + "\" (expected \"" + kShotsSchema + "\")");
  }
  RejectOutOfRangeNumbers(root);
  ShotList list;
  list.source = source;
  list.ground = std::move(ground);
  if (auto o = root.Find("origin")) {
    list.origin = ParseOrigin(*o);
    if (scene_origin && !SameOrigin(*scene_origin, *list.origin)) {
      o->Fail("differs from the scene's origin (`scene_origin`); remove it or make them agree");
    }
  } else {
    list.origin = scene_origin;
  }
  std::optional<EnuFrame> frame;
  if (list.origin) frame.emplace(*list.origin);

  if (root.Has("frame_rate_hz")) {
    list.frame_rate_hz = root["frame_rate_hz"].AsPositive();
    if (list.frame_rate_hz < 0.01 || list.frame_rate_hz > 1000) root["frame_rate_hz"].Fail("must be in [0.01, 1000]");
  }
  const auto drones = root.Find("drones");
  // With "drones", the top-level camera and drone are the defaults each drone may replace.
  if (!drones || root.Has("camera")) list.camera = ParseCamera(root["camera"]);
  list.drone = root.Has("drone") ? ParseDrone(root["drone"]) : DefaultDroneProfile();
  if (!drones || root.Has("camera")) CheckCameraAgainstFixedLens(root["camera"], list.camera, list.drone);

  if (auto actors = root.Find("actors")) {
    for (const auto& a : actors->Elements()) {
      Actor actor = ParseActor(a, PositionContext{frame ? &*frame : nullptr, list.ground.get()});
      if (list.FindActor(actor.name()) >= 0) a["name"].Fail("duplicate actor name \"" + actor.name() + "\"");
      list.actors.push_back(std::move(actor));
    }
  }
  if (drones) ParseDrones(*drones, root, frame ? &*frame : nullptr, list);

  const JsonField shots = root["shots"];
  if (shots.size() == 0) shots.Fail("must hold at least one shot");
  // Each drone's shots run back to back from t = 0; a shot is parsed against its drone's camera.
  std::vector<double> start(std::max<size_t>(list.drones.size(), 1), 0.0);
  std::vector<ShotList> drone_views;
  for (const auto& d : list.drones) {
    ShotList view;
    view.source = list.source;
    view.origin = list.origin;
    view.frame_rate_hz = list.frame_rate_hz;
    view.camera = d.camera;
    view.drone = d.drone;
    view.actors = list.actors;
    view.ground = list.ground;
    drone_views.push_back(std::move(view));
  }
  for (size_t i = 0; i < shots.size(); ++i) {
    const JsonField f = shots.At(i);
    int drone = -1;
    if (auto d = f.Find("drone")) {
      if (list.drones.empty()) d->Fail("names a drone, but the shot list has no \"drones\"");
      drone = list.FindDrone(d->AsString());
      if (drone < 0) d->Fail("no drone is named \"" + d->AsString() + "\" (see \"drones\")");
    } else if (!list.drones.empty()) {
      f.Fail("missing \"drone\": with \"drones\", every shot names the drone that flies it");
    }
    const ShotList& context = drone >= 0 ? drone_views[static_cast<size_t>(drone)] : list;
    double& drone_start = start[static_cast<size_t>(std::max(drone, 0))];
    ShotSpec s = ParseShotSpec(f, i, context, drone_start, frame ? &*frame : nullptr);
    s.drone = drone;
    for (const auto& other : list.shots) {
      if (other.name == s.name) f["name"].Fail("duplicate shot name \"" + s.name + "\"");
    }
    drone_start += s.duration_s;
    list.shots.push_back(std::move(s));
  }
  for (size_t d = 0; d < list.drones.size(); ++d) {
    bool flies = false;
    for (const auto& s : list.shots) flies = flies || s.drone == static_cast<int>(d);
    if (!flies) (*drones).At(d).Fail("drone \"" + list.drones[d].name + "\" flies no shot");
  }
  if (auto edit = root.Find("edit")) {
    if (list.drones.empty()) edit->Fail("an edit cuts between drones: it needs \"drones\"");
    ParseEdit(*edit, list);
  }
  return list;
}

ShotList ReadShotListFile(const std::filesystem::path& path, const std::optional<Geodetic>& scene_origin,
                          std::shared_ptr<const Ground> ground) {
  // Messages name the file by its base name, so they read the same wherever the file lives.
  const std::string name = path.filename().string();
  return ParseShotList(ParseJsonText(ReadFileToString(path), name), name, scene_origin, std::move(ground));
}

}  // namespace cinepath::shots
