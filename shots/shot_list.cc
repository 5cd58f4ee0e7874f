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
#include "core/scene_file.h"

namespace cinepath {
namespace {

Geodetic ParseOrigin(const JsonField& f) {
  f.RejectUnknownKeys({"lat_deg", "lon_deg", "height_m"});
  return GeodeticFromJson(f);
}

// Every number in a shot list must be within +-1e7 (m, s, deg, mm ...): far beyond any real shot,
// small enough that nothing downstream overflows.
void RejectHugeNumbers(const JsonField& f) {
  if (f.IsNumber()) {
    const double v = f.AsDouble();
    if (std::fabs(v) > 1e7) f.Fail("must be within +-1e7");
  } else if (f.IsObject()) {
    for (const auto& item : f.node().items()) RejectHugeNumbers(f[item.key()]);
  } else if (f.IsArray()) {
    for (const auto& e : f.Elements()) RejectHugeNumbers(e);
  }
}

Easing ParseEasing(const JsonField& f) {
  auto e = EasingFromName(f.AsString());
  if (!e) {
    f.Fail("unknown easing \"" + f.AsString() +
           "\" (linear, ease_in_quad, ease_out_quad, ease_in_out_quad, ease_in_cubic, ease_out_cubic, "
           "ease_in_out_cubic, ease_in_sine, ease_out_sine, ease_in_out_sine, smoothstep, smootherstep)");
  }
  return *e;
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

int ActorIndex(const ShotList& list, const JsonField& f) {
  const std::string name = f.AsString();
  const int i = list.FindActor(name);
  if (i < 0) f.Fail("no actor named \"" + name + "\"");
  return i;
}

Eigen::Vector2d ParseScreenPosition(const JsonField& f) {
  if (f.IsString()) {
    const std::string s = f.AsString();
    if (s == "center") return {0.5, 0.5};
    if (s == "left_third") return {1.0 / 3.0, 0.5};
    if (s == "right_third") return {2.0 / 3.0, 0.5};
    if (s == "upper_left_third") return {1.0 / 3.0, 1.0 / 3.0};
    if (s == "upper_right_third") return {2.0 / 3.0, 1.0 / 3.0};
    if (s == "lower_left_third") return {1.0 / 3.0, 2.0 / 3.0};
    if (s == "lower_right_third") return {2.0 / 3.0, 2.0 / 3.0};
    f.Fail("unknown screen position \"" + s +
           "\" (center, left_third, right_third, upper_left_third, upper_right_third, lower_left_third, "
           "lower_right_third, or [x, y] in [0, 1])");
  }
  if (!f.IsArray() || f.size() != 2) f.Fail("expected [x, y] (0..1 from the top-left corner) or a name");
  const double x = f.At(0).AsDouble(), y = f.At(1).AsDouble();
  if (x <= 0.0 || x >= 1.0) f.At(0).Fail("must be in (0, 1)");
  if (y <= 0.0 || y >= 1.0) f.At(1).Fail("must be in (0, 1)");
  return {x, y};
}

std::string Short(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::vector<ScalarKey> ParseScalarKeys(const JsonField& f, const char* value_key, double lo, double hi,
                                       const std::string& range_note) {
  std::vector<ScalarKey> keys;
  auto check = [&](const JsonField& v) {
    const double x = v.AsPositive();
    if (x < lo || x > hi) v.Fail("must be in [" + Short(lo) + ", " + Short(hi) + "]" + range_note);
    return x;
  };
  if (f.IsNumber()) {
    keys.push_back({0.0, check(f)});
    return keys;
  }
  if (!f.IsArray() || f.size() == 0)
    f.Fail(std::string("expected a number or [{\"time_s\", \"") + value_key + "\"}, ...]");
  for (const auto& k : f.Elements()) {
    k.RejectUnknownKeys({"time_s", value_key});
    const double t = k["time_s"].AsNonNegative();
    if (!keys.empty() && !(t >= keys.back().time_s + 1e-3))
      k["time_s"].Fail("key times must increase (by 1 ms or more)");
    keys.push_back({t, check(k[value_key])});
  }
  return keys;
}

LensSpec ParseLens(const JsonField& f, const ShotList& list, const ShotSpec& shot) {
  f.RejectUnknownKeys({"focal_length_mm", "focal_length_end_mm", "frame_height_fraction", "frame_height_fraction_end",
                       "screen_position", "focus", "rack", "f_number", "shutter_s"});
  LensSpec l;
  if (f.Has("focal_length_mm")) l.focal_length_mm = f["focal_length_mm"].AsPositive();
  if (f.Has("focal_length_end_mm")) l.focal_length_end_mm = f["focal_length_end_mm"].AsPositive();
  if (f.Has("frame_height_fraction")) l.frame_height_fraction = f["frame_height_fraction"].AsPositive();
  if (f.Has("frame_height_fraction_end")) l.frame_height_fraction_end = f["frame_height_fraction_end"].AsPositive();
  if (l.frame_height_fraction && l.focal_length_mm && shot.type != ShotType::kDollyZoom) {
    f.Fail("give either \"focal_length_mm\" or \"frame_height_fraction\", not both");
  }
  if (l.frame_height_fraction_end && !l.frame_height_fraction) {
    f["frame_height_fraction_end"].Fail("needs \"frame_height_fraction\"");
  }
  if (l.focal_length_end_mm && !l.focal_length_mm) f["focal_length_end_mm"].Fail("needs \"focal_length_mm\"");
  if ((l.frame_height_fraction || shot.type == ShotType::kDollyZoom) && shot.subject < 0) {
    f.Fail("framing needs the shot's \"subject\"");
  }
  if (auto sp = f.Find("screen_position")) l.screen_position = ParseScreenPosition(*sp);
  l.focus = shot.subject >= 0 ? LensSpec::Focus::kFollow : LensSpec::Focus::kInfinity;
  if (auto focus = f.Find("focus")) {
    if (focus->IsNumber()) {
      l.focus = LensSpec::Focus::kFixed;
      l.focus_distance_m = focus->AsPositive();
    } else {
      const std::string s = focus->AsString();
      if (s == "follow") {
        if (shot.subject < 0) focus->Fail("\"follow\" needs the shot's \"subject\"");
        l.focus = LensSpec::Focus::kFollow;
      } else if (s == "infinity") {
        l.focus = LensSpec::Focus::kInfinity;
      } else {
        focus->Fail("expected \"follow\", \"infinity\" or a distance in metres");
      }
    }
  }
  if (auto rack = f.Find("rack")) {
    for (const auto& r : rack->Elements()) {
      r.RejectUnknownKeys({"at_s", "duration_s", "subject"});
      RackFocus rf;
      rf.at_s = r["at_s"].AsNonNegative();
      rf.duration_s = r.Has("duration_s") ? r["duration_s"].AsPositive() : 1.0;
      rf.actor = ActorIndex(list, r["subject"]);
      if (!l.rack.empty() && rf.at_s < l.rack.back().at_s + l.rack.back().duration_s) {
        r["at_s"].Fail("racks must not overlap (starts before the previous rack ends)");
      }
      l.rack.push_back(rf);
    }
    if (!l.rack.empty() && l.focus != LensSpec::Focus::kFollow) rack->Fail("rack focus needs \"focus\": \"follow\"");
  }
  if (auto fn = f.Find("f_number"))
    l.f_number =
        ParseScalarKeys(*fn, "f_number", list.camera.min_f_number, list.camera.max_f_number, " (the camera's range)");
  if (auto sh = f.Find("shutter_s")) l.shutter_s = ParseScalarKeys(*sh, "shutter_s", 1e-6, 60.0, "");
  return l;
}

// Orientation given on a free keyframe: angles, or a look-at (subject or ENU point).
std::optional<Eigen::Quaterniond> ParseKeyOrientation(const JsonField& k, const ShotList& list,
                                                      const Eigen::Vector3d& pos, double key_plan_time_s) {
  const bool has_angles = k.Has("heading_deg") || k.Has("pitch_deg") || k.Has("roll_deg");
  const bool has_look = k.Has("look_at");
  if (has_angles && has_look) k.Fail("give either \"look_at\" or heading/pitch/roll angles, not both");
  if (has_angles) {
    GimbalAngles g;
    g.drone_heading_deg = k.DoubleOr("heading_deg", 0.0);
    g.gimbal_pitch_deg = k.DoubleOr("pitch_deg", 0.0);
    g.gimbal_roll_deg = k.DoubleOr("roll_deg", 0.0);
    if (g.gimbal_pitch_deg < -90 || g.gimbal_pitch_deg > 90) k["pitch_deg"].Fail("must be in [-90, 90]");
    return WorldFromCameraFromGimbal(g);
  }
  if (has_look) {
    const JsonField look = k["look_at"];
    Eigen::Vector3d target;
    if (look.IsString()) {
      target = list.actors[ActorIndex(list, look)].AimPointAt(key_plan_time_s);
    } else {
      if (!look.IsArray() || look.size() != 3) look.Fail("expected an actor name or [east_m, north_m, up_m]");
      target = {look.At(0).AsDouble(), look.At(1).AsDouble(), look.At(2).AsDouble()};
    }
    if ((target - pos).norm() < 1e-9) look.Fail("the camera is on the look-at point");
    return LookAt(target - pos);
  }
  return std::nullopt;
}

double ParseDirection(const JsonField& f) {
  const std::string d = f.AsString();
  if (d == "cw" || d == "clockwise") return 1.0;
  if (d == "ccw" || d == "counterclockwise") return -1.0;
  f.Fail("expected \"cw\" or \"ccw\"");
}

double ParseSide(const JsonField& f) {
  const std::string s = f.AsString();
  if (s == "right") return 1.0;
  if (s == "left") return -1.0;
  f.Fail("expected \"left\" or \"right\"");
}

ShotSpec ParseShot(const JsonField& f, size_t index, const ShotList& list, double shot_start_s, const EnuFrame* frame) {
  ShotSpec s;
  const std::string type_name = f["type"].AsString();
  auto type = ShotTypeFromName(type_name);
  if (!type) {
    std::string names;
    for (auto n : ShotTypeNames()) names += (names.empty() ? "" : ", ") + std::string(n);
    f["type"].Fail("unknown shot type \"" + type_name + "\" (" + names + ")");
  }
  s.type = *type;
  s.type_name = type_name;
  s.name = f.StringOr("name", "shot" + std::to_string(index + 1));

  std::vector<std::string_view> allowed = {"name",   "type",       "subject", "duration_s",
                                           "easing", "transition", "blend_s", "lens"};
  auto allow = [&](std::initializer_list<std::string_view> keys) { allowed.insert(allowed.end(), keys); };
  switch (s.type) {
    case ShotType::kChase: allow({"distance_m", "height_m", "lateral_m", "lag_s"}); break;
    case ShotType::kOrbit:
      allow({"radius_m", "height_m", "turns", "angular_speed_deg_s", "direction", "start_bearing_deg"});
      break;
    case ShotType::kHelix:
      allow({"radius_m", "radius_end_m", "height_m", "height_end_m", "turns", "angular_speed_deg_s", "direction",
             "start_bearing_deg"});
      break;
    case ShotType::kFlyby:
      allow({"closest_distance_m", "side", "height_m", "speed_m_s", "travel_bearing_deg", "closest_at_s"});
      break;
    case ShotType::kDolly:
      allow({"distance_m", "side", "height_m", "along_start_m", "along_end_m", "travel_bearing_deg"});
      break;
    case ShotType::kCrane:
    case ShotType::kDronie:
      allow({"distance_m", "distance_end_m", "height_m", "height_end_m", "bearing_deg", "tilt_start_deg"});
      break;
    case ShotType::kTopDown: allow({"height_m", "height_end_m", "up_bearing_deg", "rotate_deg", "offset_enu_m"}); break;
    case ShotType::kDollyZoom: allow({"distance_m", "distance_end_m", "height_m", "bearing_deg"}); break;
    case ShotType::kLockedOff:
      allow({"position_enu_m", "position", "bearing_deg", "distance_m", "height_m", "heading_deg", "pitch_deg", "pan"});
      break;
    case ShotType::kKeyframes: allow({"keys", "interpolation", "orientation"}); break;
  }
  {
    // RejectUnknownKeys takes an initializer_list; check by hand against the vector.
    for (const auto& item : f.node().items()) {
      bool ok = false;
      for (auto k : allowed) ok = ok || k == item.key();
      if (!ok) f[item.key()].Fail("unknown key for a " + std::string(ShotTypeName(s.type)) + " shot");
    }
  }

  if (auto subj = f.Find("subject")) s.subject = ActorIndex(list, *subj);
  const bool needs_subject = s.type != ShotType::kLockedOff && s.type != ShotType::kKeyframes;
  if (needs_subject && s.subject < 0) f.Fail("a " + std::string(ShotTypeName(s.type)) + " shot needs a \"subject\"");

  if (s.type == ShotType::kKeyframes && !f.Has("duration_s")) {
    // Defaults to the last key's time (read below).
  } else {
    s.duration_s = f["duration_s"].AsNonNegative();
    if (s.duration_s > 1e7) f["duration_s"].Fail("must be <= 1e7 s");
  }
  if (auto e = f.Find("easing")) s.easing = ParseEasing(*e);
  if (auto tr = f.Find("transition")) {
    const std::string t = tr->AsString();
    if (t == "cut") {
      s.cut = true;
    } else if (t != "continuous") {
      tr->Fail("expected \"continuous\" or \"cut\"");
    }
  }
  if (f.Has("blend_s")) s.blend_s = f["blend_s"].AsNonNegative();

  auto positive = [&](const char* key) { return f[key].AsPositive(); };
  auto number_or = [&](const char* key, double fallback) { return f.DoubleOr(key, fallback); };
  auto sweep = [&]() {
    const bool has_turns = f.Has("turns"), has_rate = f.Has("angular_speed_deg_s");
    if (has_turns == has_rate) f.Fail("give exactly one of \"turns\" or \"angular_speed_deg_s\"");
    const double dir = f.Has("direction") ? ParseDirection(f["direction"]) : -1.0;
    const double deg =
        has_turns ? 360.0 * f["turns"].AsNonNegative() : f["angular_speed_deg_s"].AsNonNegative() * s.duration_s;
    s.total_angle_deg = dir * deg;
    s.start_bearing_deg = number_or("start_bearing_deg", 0.0);
  };
  const double subject_height = s.subject >= 0 ? list.actors[s.subject].height_m() : 0.0;

  switch (s.type) {
    case ShotType::kChase:
      s.distance_m = positive("distance_m");
      s.height_m = f["height_m"].AsDouble();
      s.lateral_m = number_or("lateral_m", 0.0);
      s.lag_s = f.Has("lag_s") ? f["lag_s"].AsNonNegative() : 0.0;
      break;
    case ShotType::kOrbit:
      s.radius_m = s.radius_end_m = positive("radius_m");
      s.height_m = s.height_end_m = f["height_m"].AsDouble();
      sweep();
      break;
    case ShotType::kHelix:
      s.radius_m = positive("radius_m");
      s.radius_end_m = f.Has("radius_end_m") ? positive("radius_end_m") : s.radius_m;
      s.height_m = f["height_m"].AsDouble();
      s.height_end_m = f["height_end_m"].AsDouble();
      sweep();
      break;
    case ShotType::kFlyby:
      s.distance_m = positive("closest_distance_m");
      s.side = f.Has("side") ? ParseSide(f["side"]) : 1.0;
      s.height_m = f["height_m"].AsDouble();
      s.speed_m_s = positive("speed_m_s");
      if (f.Has("travel_bearing_deg")) s.travel_bearing_deg = f["travel_bearing_deg"].AsDouble();
      s.closest_at_s = f.Has("closest_at_s") ? f["closest_at_s"].AsNonNegative() : s.duration_s / 2;
      break;
    case ShotType::kDolly:
      s.distance_m = positive("distance_m");
      s.side = f.Has("side") ? ParseSide(f["side"]) : 1.0;
      s.height_m = number_or("height_m", subject_height / 2);
      s.along_start_m = number_or("along_start_m", 0.0);
      s.along_end_m = number_or("along_end_m", s.along_start_m);
      if (f.Has("travel_bearing_deg")) s.travel_bearing_deg = f["travel_bearing_deg"].AsDouble();
      break;
    case ShotType::kCrane:
    case ShotType::kDronie:
      s.distance_m = positive("distance_m");
      s.distance_end_m = f.Has("distance_end_m") ? positive("distance_end_m") : s.distance_m;
      s.height_m = f["height_m"].AsDouble();
      s.height_end_m = f["height_end_m"].AsDouble();
      s.bearing_deg = number_or("bearing_deg", 180.0);
      if (f.Has("tilt_start_deg")) {
        s.tilt_start_deg = f["tilt_start_deg"].AsDouble();
        if (*s.tilt_start_deg < -90 || *s.tilt_start_deg > 90) f["tilt_start_deg"].Fail("must be in [-90, 90]");
      }
      if (s.type == ShotType::kDronie && s.distance_end_m <= s.distance_m) {
        f["distance_end_m"].Fail("a DRONIE flies away: must be > distance_m");
      }
      break;
    case ShotType::kTopDown:
      s.height_m = positive("height_m");
      s.height_end_m = f.Has("height_end_m") ? positive("height_end_m") : s.height_m;
      s.up_bearing_deg = number_or("up_bearing_deg", 0.0);
      s.rotate_deg = number_or("rotate_deg", 0.0);
      if (auto off = f.Find("offset_enu_m")) {
        if (!off->IsArray() || off->size() != 3) off->Fail("expected [east_m, north_m, up_m]");
        s.offset_enu_m = {off->At(0).AsDouble(), off->At(1).AsDouble(), off->At(2).AsDouble()};
      }
      break;
    case ShotType::kDollyZoom:
      s.distance_m = positive("distance_m");
      s.distance_end_m = positive("distance_end_m");
      s.height_m = number_or("height_m", subject_height / 2);
      s.bearing_deg = number_or("bearing_deg", 180.0);
      break;
    case ShotType::kLockedOff:
      if (f.Has("position_enu_m") || f.Has("position")) {
        s.position_enu_m = ParsePosition(f, "position_enu_m", "position", frame);
      } else {
        if (s.subject < 0)
          f.Fail("a LOCKED-OFF shot needs a position, or a subject with distance_m/bearing_deg/height_m");
        s.distance_m = positive("distance_m");
        s.bearing_deg = number_or("bearing_deg", 180.0);
        s.height_m = f["height_m"].AsDouble();
      }
      s.pan = f.BoolOr("pan", false);
      if (s.subject < 0) {
        s.heading_deg = number_or("heading_deg", 0.0);
        s.pitch_deg = number_or("pitch_deg", 0.0);
        if (s.pitch_deg < -90 || s.pitch_deg > 90) f["pitch_deg"].Fail("must be in [-90, 90]");
        if (s.pan) f["pan"].Fail("panning needs a subject");
      }
      break;
    case ShotType::kKeyframes: {
      if (auto interp = f.Find("interpolation")) {
        auto k = PathInterpolationFromName(interp->AsString());
        if (!k) interp->Fail("expected \"linear\", \"catmull_rom\" or \"cubic_bspline\"");
        s.interpolation = *k;
      }
      if (auto o = f.Find("orientation")) {
        const std::string name = o->AsString();
        if (name == "slerp") {
          s.orientation = OrientationInterpolation::kSlerp;
        } else if (name != "squad") {
          o->Fail("expected \"slerp\" or \"squad\"");
        }
      }
      const JsonField keys = f["keys"];
      if (keys.size() == 0) keys.Fail("must hold at least one key");
      bool any_orientation = false;
      for (const auto& k : keys.Elements()) {
        k.RejectUnknownKeys({"time_s", "position_enu_m", "position", "look_at", "heading_deg", "pitch_deg", "roll_deg",
                             "focal_length_mm", "focus_distance_m", "f_number", "easing"});
        CameraKey key;
        key.time_s = k["time_s"].AsNonNegative();
        if (!s.keys.empty() && !(key.time_s >= s.keys.back().time_s + 1e-3))
          k["time_s"].Fail("key times must increase (by 1 ms or more)");
        key.position_enu_m = ParsePosition(k, "position_enu_m", "position", frame);
        key.world_from_camera = ParseKeyOrientation(k, list, key.position_enu_m, shot_start_s + key.time_s);
        any_orientation = any_orientation || key.world_from_camera.has_value();
        if (k.Has("focal_length_mm")) key.focal_length_mm = k["focal_length_mm"].AsPositive();
        if (auto fd = k.Find("focus_distance_m")) key.focus_distance_m = fd->AsPositive();
        if (k.node().contains("focus_distance_m") && k.node()["focus_distance_m"].is_null()) {
          key.focus_distance_m = std::numeric_limits<double>::infinity();
        }
        if (k.Has("f_number")) key.f_number = k["f_number"].AsPositive();
        if (auto e = k.Find("easing")) key.easing = ParseEasing(*e);
        s.keys.push_back(key);
      }
      if (any_orientation || s.subject < 0) {
        for (size_t i = 0; i < s.keys.size(); ++i) {
          if (!s.keys[i].world_from_camera) {
            keys.At(i).Fail(s.subject < 0
                                ? "needs an orientation (look_at or heading/pitch/roll): the shot has no subject"
                                : "needs an orientation: when one key gives one, all must");
          }
        }
      }
      const double last = s.keys.back().time_s;
      if (f.Has("duration_s")) {
        if (s.duration_s < last) f["duration_s"].Fail("must be >= the last key's time_s");
      } else {
        s.duration_s = last;
      }
      break;
    }
  }
  if (auto lens = f.Find("lens")) {
    s.lens = ParseLens(*lens, list, s);
  } else {
    LensSpec l;
    l.focus = s.subject >= 0 ? LensSpec::Focus::kFollow : LensSpec::Focus::kInfinity;
    s.lens = l;
    if (s.type == ShotType::kDollyZoom)
      f.Fail("a DOLLY-ZOOM shot needs \"lens\" with frame_height_fraction or focal_length_mm");
  }
  if (s.type == ShotType::kDollyZoom && !s.lens.frame_height_fraction && !s.lens.focal_length_mm) {
    f["lens"].Fail("a DOLLY-ZOOM shot needs frame_height_fraction or focal_length_mm");
  }
  for (const auto& r : s.lens.rack) {
    if (r.at_s > s.duration_s) f["lens"]["rack"].Fail("a rack starts after the shot ends");
  }
  return s;
}

}  // namespace

int ShotList::FindActor(const std::string& name) const {
  for (size_t i = 0; i < actors.size(); ++i) {
    if (actors[i].name() == name) return static_cast<int>(i);
  }
  return -1;
}

ShotList ParseShotList(const Json& document, const std::string& source, const std::optional<Geodetic>& scene_origin) {
  const JsonField root(document, source);
  if (!root.IsObject()) root.Fail("expected a shot list (a JSON object)");
  root.RejectUnknownKeys({"schema", "origin", "frame_rate_hz", "camera", "drone", "actors", "shots", "description"});
  const std::string schema = root["schema"].AsString();
  if (schema != kShotsSchema) {
    root["schema"].Fail("unsupported shot-list version \"" + schema + "\" (expected \"" + kShotsSchema + "\")");
  }
  RejectHugeNumbers(root);
  ShotList list;
  list.source = source;
  if (auto o = root.Find("origin")) {
    list.origin = ParseOrigin(*o);
    if (scene_origin && (std::fabs(scene_origin->lat_deg - list.origin->lat_deg) > 1e-9 ||
                         std::fabs(scene_origin->lon_deg - list.origin->lon_deg) > 1e-9 ||
                         std::fabs(scene_origin->height_m - list.origin->height_m) > 1e-6)) {
      o->Fail("differs from the scene's origin (--scene); remove it or make them agree");
    }
  } else {
    list.origin = scene_origin;
  }
  std::optional<EnuFrame> frame;
  if (list.origin) frame.emplace(*list.origin);

  if (root.Has("frame_rate_hz")) {
    list.frame_rate_hz = root["frame_rate_hz"].AsPositive();
    if (list.frame_rate_hz > 1000) root["frame_rate_hz"].Fail("must be <= 1000");
  }
  list.camera = ParseCamera(root["camera"]);
  list.drone = root.Has("drone") ? ParseDrone(root["drone"]) : DefaultDroneProfile();
  CheckCameraAgainstFixedLens(root["camera"], list.camera, list.drone);

  if (auto actors = root.Find("actors")) {
    for (const auto& a : actors->Elements()) {
      Actor actor = ParseActor(a, frame ? &*frame : nullptr);
      if (list.FindActor(actor.name()) >= 0) a["name"].Fail("duplicate actor name \"" + actor.name() + "\"");
      list.actors.push_back(std::move(actor));
    }
  }
  const JsonField shots = root["shots"];
  if (shots.size() == 0) shots.Fail("must hold at least one shot");
  double start = 0;
  for (size_t i = 0; i < shots.size(); ++i) {
    ShotSpec s = ParseShot(shots.At(i), i, list, start, frame ? &*frame : nullptr);
    for (const auto& other : list.shots) {
      if (other.name == s.name) shots.At(i)["name"].Fail("duplicate shot name \"" + s.name + "\"");
    }
    start += s.duration_s;
    list.shots.push_back(std::move(s));
  }
  return list;
}

ShotList ReadShotListFile(const std::filesystem::path& path, const std::optional<Geodetic>& scene_origin) {
  // Messages name the file by its base name, so they read the same wherever the file lives.
  const std::string name = path.filename().string();
  return ParseShotList(ParseJsonText(ReadFileToString(path), name), name, scene_origin);
}

std::optional<Geodetic> ReadSceneOrigin(const std::filesystem::path& scene_json) {
  return ReadSceneFile(scene_json).origin;
}

}  // namespace cinepath
