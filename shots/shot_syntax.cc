#include "shots/shot_syntax.h"

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/local_level.h"
#include "core/number_format.h"
#include "core/plan_file.h"
#include "core/rotation.h"

namespace cinepath::shots {
namespace {

// What a type's reader needs besides the shot's own JSON object.
struct ShotContext {
  const ShotList& list;
  double shot_start_s;
  PositionContext positions;  // frame and ground
};

Easing ParseEasing(const JsonField& f) {
  auto e = EasingFromName(f.AsString());
  if (!e) {
    f.Fail("unknown easing \"" + f.AsString() +
           "\" (linear, ease_in_quad, ease_out_quad, ease_in_out_quad, ease_in_cubic, ease_out_cubic, "
           "ease_in_out_cubic, ease_in_sine, ease_out_sine, ease_in_out_sine, smoothstep, smootherstep)");
  }
  return *e;
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

std::vector<ScalarKey> ParseScalarKeys(const JsonField& f, const char* value_key, double lo, double hi,
                                       const std::string& range_note) {
  std::vector<ScalarKey> keys;
  auto check = [&](const JsonField& v) {
    const double x = v.AsPositive();
    if (x < lo || x > hi)
      v.Fail("must be in [" + FormatSignificant(lo) + ", " + FormatSignificant(hi) + "]" + range_note);
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
                       "screen_position", "focus", "rack", "f_number", "shutter_s", "sharp", "background_blur_px",
                       "background_distance_m"});
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
  if (auto sharp = f.Find("sharp")) {
    for (const auto& e : sharp->Elements()) l.sharp.push_back(ActorIndex(list, e));
  }
  if (f.Has("background_blur_px")) l.background_blur_px = f["background_blur_px"].AsPositive();
  if (f.Has("background_distance_m")) l.background_distance_m = f["background_distance_m"].AsPositive();
  if ((l.background_blur_px || !l.sharp.empty()) && shot.subject < 0 && l.sharp.empty()) {
    f.Fail("a background_blur_px goal needs the shot's \"subject\" or a \"sharp\" list");
  }
  if (auto fn = f.Find("f_number"))
    l.f_number =
        ParseScalarKeys(*fn, "f_number", list.camera.min_f_number, list.camera.max_f_number, " (the camera's range)");
  if (auto sh = f.Find("shutter_s")) l.shutter_s = ParseScalarKeys(*sh, "shutter_s", 1e-6, 60.0, "");
  return l;
}

// Orientation given on a free keyframe: angles, or a look-at (subject or ENU point).
std::optional<Eigen::Quaterniond> ParseKeyOrientation(const JsonField& k, const ShotContext& c,
                                                      const Eigen::Vector3d& pos, double key_plan_time_s) {
  const ShotList& list = c.list;
  const bool has_angles = k.Has("heading_deg") || k.Has("pitch_deg") || k.Has("roll_deg");
  const bool has_look = k.Has("look_at");
  if (has_angles && has_look) k.Fail("give either \"look_at\" or heading/pitch/roll angles, not both");
  if (has_angles) {
    GimbalAngles g;
    g.drone_heading_deg = k.DoubleOr("heading_deg", 0.0);
    g.gimbal_pitch_deg = k.DoubleOr("pitch_deg", 0.0);
    g.gimbal_roll_deg = k.DoubleOr("roll_deg", 0.0);
    if (g.gimbal_pitch_deg < -90 || g.gimbal_pitch_deg > 90) k["pitch_deg"].Fail("must be in [-90, 90]");
    return LocalWorldFromCamera(c.positions.frame, pos, g);  // true north and the vertical at the key
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
    return LocalLookAt(c.positions.frame, pos, target - pos);  // level where the key is
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

// ORBIT and HELIX: "turns" or "angular_speed_deg_s", "direction", "start_bearing_deg".
void ParseSweep(const JsonField& f, ShotSpec& s) {
  const bool has_turns = f.Has("turns"), has_rate = f.Has("angular_speed_deg_s");
  if (has_turns == has_rate) f.Fail("give exactly one of \"turns\" or \"angular_speed_deg_s\"");
  const double dir = f.Has("direction") ? ParseDirection(f["direction"]) : -1.0;
  const double deg =
      has_turns ? 360.0 * f["turns"].AsNonNegative() : f["angular_speed_deg_s"].AsNonNegative() * s.duration_s;
  s.total_angle_deg = dir * deg;
  s.start_bearing_deg = f.DoubleOr("start_bearing_deg", 0.0);
}

double SubjectHeightM(const ShotContext& c, const ShotSpec& s) {
  return s.subject >= 0 ? c.list.actors[s.subject].height_m() : 0.0;
}

void ParseChase(const JsonField& f, const ShotContext&, ShotSpec& s) {
  s.distance_m = f["distance_m"].AsPositive();
  s.height_m = f["height_m"].AsDouble();
  s.lateral_m = f.DoubleOr("lateral_m", 0.0);
  s.lag_s = f.Has("lag_s") ? f["lag_s"].AsNonNegative() : 0.0;
}

void ParseOrbit(const JsonField& f, const ShotContext&, ShotSpec& s) {
  s.radius_m = s.radius_end_m = f["radius_m"].AsPositive();
  s.height_m = s.height_end_m = f["height_m"].AsDouble();
  ParseSweep(f, s);
}

void ParseHelix(const JsonField& f, const ShotContext&, ShotSpec& s) {
  s.radius_m = f["radius_m"].AsPositive();
  s.radius_end_m = f.Has("radius_end_m") ? f["radius_end_m"].AsPositive() : s.radius_m;
  s.height_m = f["height_m"].AsDouble();
  s.height_end_m = f["height_end_m"].AsDouble();
  ParseSweep(f, s);
}

void ParseFlyby(const JsonField& f, const ShotContext&, ShotSpec& s) {
  s.distance_m = f["closest_distance_m"].AsPositive();
  s.side = f.Has("side") ? ParseSide(f["side"]) : 1.0;
  s.height_m = f["height_m"].AsDouble();
  s.speed_m_s = f["speed_m_s"].AsPositive();
  if (f.Has("travel_bearing_deg")) s.travel_bearing_deg = f["travel_bearing_deg"].AsDouble();
  s.closest_at_s = f.Has("closest_at_s") ? f["closest_at_s"].AsNonNegative() : s.duration_s / 2;
}

void ParseDolly(const JsonField& f, const ShotContext& c, ShotSpec& s) {
  s.distance_m = f["distance_m"].AsPositive();
  s.side = f.Has("side") ? ParseSide(f["side"]) : 1.0;
  s.height_m = f.DoubleOr("height_m", SubjectHeightM(c, s) / 2);
  s.along_start_m = f.DoubleOr("along_start_m", 0.0);
  s.along_end_m = f.DoubleOr("along_end_m", s.along_start_m);
  if (f.Has("travel_bearing_deg")) s.travel_bearing_deg = f["travel_bearing_deg"].AsDouble();
}

// CRANE / REVEAL and DRONIE share their keys; a DRONIE must fly away.
void ParseCraneOrDronie(const JsonField& f, const ShotContext&, ShotSpec& s) {
  s.distance_m = f["distance_m"].AsPositive();
  s.distance_end_m = f.Has("distance_end_m") ? f["distance_end_m"].AsPositive() : s.distance_m;
  s.height_m = f["height_m"].AsDouble();
  s.height_end_m = f["height_end_m"].AsDouble();
  s.bearing_deg = f.DoubleOr("bearing_deg", 180.0);
  if (f.Has("tilt_start_deg")) {
    s.tilt_start_deg = f["tilt_start_deg"].AsDouble();
    if (*s.tilt_start_deg < -90 || *s.tilt_start_deg > 90) f["tilt_start_deg"].Fail("must be in [-90, 90]");
  }
  if (s.type == ShotType::kDronie && s.distance_end_m <= s.distance_m) {
    f["distance_end_m"].Fail("a DRONIE flies away: must be > distance_m");
  }
}

void ParseTopDown(const JsonField& f, const ShotContext&, ShotSpec& s) {
  s.height_m = f["height_m"].AsPositive();
  s.height_end_m = f.Has("height_end_m") ? f["height_end_m"].AsPositive() : s.height_m;
  s.up_bearing_deg = f.DoubleOr("up_bearing_deg", 0.0);
  s.rotate_deg = f.DoubleOr("rotate_deg", 0.0);
  if (auto off = f.Find("offset_enu_m")) {
    if (!off->IsArray() || off->size() != 3) off->Fail("expected [east_m, north_m, up_m]");
    s.offset_enu_m = {off->At(0).AsDouble(), off->At(1).AsDouble(), off->At(2).AsDouble()};
  }
}

void ParseDollyZoom(const JsonField& f, const ShotContext& c, ShotSpec& s) {
  s.distance_m = f["distance_m"].AsPositive();
  s.distance_end_m = f["distance_end_m"].AsPositive();
  s.height_m = f.DoubleOr("height_m", SubjectHeightM(c, s) / 2);
  s.bearing_deg = f.DoubleOr("bearing_deg", 180.0);
}

void ParseLockedOff(const JsonField& f, const ShotContext& c, ShotSpec& s) {
  if (f.Has("position_enu_m") || f.Has("position")) {
    s.position_enu_m = ParsePosition(f, "position_enu_m", "position", c.positions);
  } else {
    if (s.subject < 0) f.Fail("a LOCKED-OFF shot needs a position, or a subject with distance_m/bearing_deg/height_m");
    s.distance_m = f["distance_m"].AsPositive();
    s.bearing_deg = f.DoubleOr("bearing_deg", 180.0);
    s.height_m = f["height_m"].AsDouble();
  }
  s.pan = f.BoolOr("pan", false);
  if (s.subject < 0) {
    GimbalAngles g;
    g.drone_heading_deg = f.DoubleOr("heading_deg", 0.0);
    g.gimbal_pitch_deg = f.DoubleOr("pitch_deg", 0.0);
    if (g.gimbal_pitch_deg < -90 || g.gimbal_pitch_deg > 90) f["pitch_deg"].Fail("must be in [-90, 90]");
    s.locked_world_from_camera = LocalWorldFromCamera(c.positions.frame, *s.position_enu_m, g);
    if (s.pan) f["pan"].Fail("panning needs a subject");
  }
}

// One free key of a KEYFRAMES shot.
CameraKey ParseCameraKey(const JsonField& k, const ShotContext& c) {
  k.RejectUnknownKeys({"time_s", "position_enu_m", "position", "above_ground_m", "look_at", "heading_deg", "pitch_deg",
                       "roll_deg", "focal_length_mm", "focus_distance_m", "f_number", "easing"});
  CameraKey key;
  key.time_s = k["time_s"].AsNonNegative();
  key.position_enu_m = ParsePosition(k, "position_enu_m", "position", c.positions);
  key.world_from_camera = ParseKeyOrientation(k, c, key.position_enu_m, c.shot_start_s + key.time_s);
  if (k.Has("focal_length_mm")) key.focal_length_mm = k["focal_length_mm"].AsPositive();
  if (auto fd = k.Find("focus_distance_m")) key.focus_distance_m = fd->AsPositive();
  if (k.node().contains("focus_distance_m") && k.node()["focus_distance_m"].is_null()) {
    key.focus_distance_m = std::numeric_limits<double>::infinity();
  }
  if (k.Has("f_number")) key.f_number = k["f_number"].AsPositive();
  if (auto e = k.Find("easing")) key.easing = ParseEasing(*e);
  return key;
}

void ParseKeyframes(const JsonField& f, const ShotContext& c, ShotSpec& s) {
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
    CameraKey key = ParseCameraKey(k, c);
    if (!s.keys.empty() && !(key.time_s >= s.keys.back().time_s + 1e-3)) {
      k["time_s"].Fail("key times must increase (by 1 ms or more)");
    }
    any_orientation = any_orientation || key.world_from_camera.has_value();
    s.keys.push_back(key);
  }
  if (any_orientation || s.subject < 0) {
    for (size_t i = 0; i < s.keys.size(); ++i) {
      if (!s.keys[i].world_from_camera) {
        keys.At(i).Fail(s.subject < 0 ? "needs an orientation (look_at or heading/pitch/roll): the shot has no subject"
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
}

// The declaration: each type's own keys, whether it needs a subject, and its reader.
struct ShotSyntax {
  ShotType type;
  std::vector<std::string_view> keys;
  bool needs_subject;
  void (*parse)(const JsonField& f, const ShotContext& c, ShotSpec& s);
};

const std::vector<ShotSyntax>& Syntax() {
  static const std::vector<ShotSyntax> syntax = {
      {ShotType::kChase, {"distance_m", "height_m", "height_reference", "lateral_m", "lag_s"}, true, &ParseChase},
      {ShotType::kOrbit,
       {"radius_m", "height_m", "height_reference", "turns", "angular_speed_deg_s", "direction", "start_bearing_deg"},
       true,
       &ParseOrbit},
      {ShotType::kHelix,
       {"radius_m", "radius_end_m", "height_m", "height_end_m", "height_reference", "turns", "angular_speed_deg_s",
        "direction", "start_bearing_deg"},
       true,
       &ParseHelix},
      {ShotType::kFlyby,
       {"closest_distance_m", "side", "height_m", "height_reference", "speed_m_s", "travel_bearing_deg",
        "closest_at_s"},
       true,
       &ParseFlyby},
      {ShotType::kDolly,
       {"distance_m", "side", "height_m", "height_reference", "along_start_m", "along_end_m", "travel_bearing_deg"},
       true,
       &ParseDolly},
      {ShotType::kCrane,
       {"distance_m", "distance_end_m", "height_m", "height_end_m", "height_reference", "bearing_deg",
        "tilt_start_deg"},
       true,
       &ParseCraneOrDronie},
      {ShotType::kDronie,
       {"distance_m", "distance_end_m", "height_m", "height_end_m", "height_reference", "bearing_deg",
        "tilt_start_deg"},
       true,
       &ParseCraneOrDronie},
      {ShotType::kTopDown,
       {"height_m", "height_end_m", "up_bearing_deg", "rotate_deg", "offset_enu_m"},
       true,
       &ParseTopDown},
      {ShotType::kDollyZoom,
       {"distance_m", "distance_end_m", "height_m", "height_reference", "bearing_deg"},
       true,
       &ParseDollyZoom},
      {ShotType::kLockedOff,
       {"position_enu_m", "position", "above_ground_m", "bearing_deg", "distance_m", "height_m", "height_reference",
        "heading_deg", "pitch_deg", "pan"},
       false,
       &ParseLockedOff},
      {ShotType::kKeyframes, {"keys", "interpolation", "orientation"}, false, &ParseKeyframes},
  };
  return syntax;
}

const ShotSyntax& SyntaxOf(ShotType type) {
  for (const ShotSyntax& s : Syntax()) {
    if (s.type == type) return s;
  }
  CINEPATH_CHECK(false);
  return Syntax().front();
}

ShotType ParseShotType(const JsonField& f) {
  const std::string name = f.AsString();
  const auto type = ShotTypeFromName(name);
  if (!type) {
    std::string names;
    for (auto n : ShotTypeNames()) names += (names.empty() ? "" : ", ") + std::string(n);
    f.Fail("unknown shot type \"" + name + "\" (" + names + ")");
  }
  return *type;
}

// The keys every shot takes: subject, duration, easing, transition, blend.
void ParseCommonKeys(const JsonField& f, const ShotSyntax& syntax, const ShotList& list, ShotSpec& s) {
  if (auto subj = f.Find("subject")) s.subject = ActorIndex(list, *subj);
  if (syntax.needs_subject && s.subject < 0) {
    f.Fail("a " + std::string(ShotTypeName(s.type)) + " shot needs a \"subject\"");
  }
  // A KEYFRAMES shot's duration defaults to its last key's time (ParseKeyframes).
  if (s.type != ShotType::kKeyframes || f.Has("duration_s")) {
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
  if (auto ref = f.Find("height_reference")) {
    const std::string r = ref->AsString();
    if (r == "ground") {
      if (!list.ground) ref->Fail("\"ground\" needs the scene's mesh (`scene_mesh`)");
      s.height_reference = HeightReference::kGround;
    } else if (r != "subject") {
      ref->Fail(
          "expected \"subject\" (height above the subject's base) or \"ground\" (above the terrain under "
          "the camera)");
    }
  }
}

// The lens block, and what a shot type demands of it.
// The shot-level "optimize" block: {"hold": [...], "max_deviation_m": m, "retime": bool}.
OptimizeSpec ParseOptimize(const JsonField& f) {
  f.RejectUnknownKeys({"hold", "max_deviation_m", "retime"});
  OptimizeSpec spec;
  if (auto hold = f.Find("hold")) spec.hold = ReadHoldList(*hold);
  if (f.Has("max_deviation_m")) spec.max_deviation_m = f["max_deviation_m"].AsNonNegative();
  if (f.Has("retime")) spec.retime = f["retime"].AsBool();
  return spec;
}

void ParseShotLens(const JsonField& f, const ShotList& list, ShotSpec& s) {
  if (auto lens = f.Find("lens")) {
    s.lens = ParseLens(*lens, list, s);
  } else {
    s.lens = LensSpec();
    s.lens.focus = s.subject >= 0 ? LensSpec::Focus::kFollow : LensSpec::Focus::kInfinity;
    if (s.type == ShotType::kDollyZoom) {
      f.Fail("a DOLLY-ZOOM shot needs \"lens\" with frame_height_fraction or focal_length_mm");
    }
  }
  if (s.type == ShotType::kDollyZoom && !s.lens.frame_height_fraction && !s.lens.focal_length_mm) {
    f["lens"].Fail("a DOLLY-ZOOM shot needs frame_height_fraction or focal_length_mm");
  }
  for (const auto& r : s.lens.rack) {
    if (r.at_s > s.duration_s) f["lens"]["rack"].Fail("a rack starts after the shot ends");
  }
}

}  // namespace

const std::vector<std::string_view>& CommonShotKeys() {
  static const std::vector<std::string_view> keys = {"name",       "type",    "subject", "duration_s", "easing",
                                                     "transition", "blend_s", "lens",    "optimize",   "drone"};
  return keys;
}

const std::vector<std::string_view>& ShotTypeKeys(ShotType type) { return SyntaxOf(type).keys; }

ShotSpec ParseShotSpec(const JsonField& f, size_t index, const ShotList& list, double shot_start_s,
                       const EnuFrame* frame) {
  const PositionContext positions{frame, list.ground.get()};
  ShotSpec s;
  s.type = ParseShotType(f["type"]);
  s.type_name = f["type"].AsString();
  s.name = f.StringOr("name", "shot" + std::to_string(index + 1));
  const ShotSyntax& syntax = SyntaxOf(s.type);
  std::vector<std::string_view> known = CommonShotKeys();
  known.insert(known.end(), syntax.keys.begin(), syntax.keys.end());
  f.RejectUnknownKeys(known, "unknown key for a " + std::string(ShotTypeName(s.type)) + " shot");
  ParseCommonKeys(f, syntax, list, s);
  syntax.parse(f, ShotContext{list, shot_start_s, positions}, s);
  ParseShotLens(f, list, s);
  if (auto optimize = f.Find("optimize")) s.optimize = ParseOptimize(*optimize);
  return s;
}

}  // namespace cinepath::shots
