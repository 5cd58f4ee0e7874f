#include "shots/shot_list.h"

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

}  // namespace

int ShotList::FindActor(const std::string& name) const {
  for (size_t i = 0; i < actors.size(); ++i) {
    if (actors[i].name() == name) return static_cast<int>(i);
  }
  return -1;
}

ShotList ParseShotList(const Json& document, const std::string& source, const std::optional<Geodetic>& scene_origin,
                       std::shared_ptr<const Ground> ground) {
  const JsonField root(document, source);
  if (!root.IsObject()) root.Fail("expected a shot list (a JSON object)");
  root.RejectUnknownKeys({"schema", "origin", "frame_rate_hz", "camera", "drone", "actors", "shots", "description"});
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
    if (scene_origin && (std::fabs(scene_origin->lat_deg - list.origin->lat_deg) > 1e-9 ||
                         std::fabs(scene_origin->lon_deg - list.origin->lon_deg) > 1e-9 ||
                         std::fabs(scene_origin->height_m - list.origin->height_m) > 1e-6)) {
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
  list.camera = ParseCamera(root["camera"]);
  list.drone = root.Has("drone") ? ParseDrone(root["drone"]) : DefaultDroneProfile();
  CheckCameraAgainstFixedLens(root["camera"], list.camera, list.drone);

  if (auto actors = root.Find("actors")) {
    for (const auto& a : actors->Elements()) {
      Actor actor = ParseActor(a, PositionContext{frame ? &*frame : nullptr, list.ground.get()});
      if (list.FindActor(actor.name()) >= 0) a["name"].Fail("duplicate actor name \"" + actor.name() + "\"");
      list.actors.push_back(std::move(actor));
    }
  }
  const JsonField shots = root["shots"];
  if (shots.size() == 0) shots.Fail("must hold at least one shot");
  double start = 0;
  for (size_t i = 0; i < shots.size(); ++i) {
    ShotSpec s = ParseShotSpec(shots.At(i), i, list, start, frame ? &*frame : nullptr);
    for (const auto& other : list.shots) {
      if (other.name == s.name) shots.At(i)["name"].Fail("duplicate shot name \"" + s.name + "\"");
    }
    start += s.duration_s;
    list.shots.push_back(std::move(s));
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
