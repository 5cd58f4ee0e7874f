#include "core/plan_file.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/drone_profiles.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/geodetic_json.h"
#include "core/number_format.h"
#include "core/version.h"

namespace cinepath {
namespace {

constexpr int kMetres = 6;
constexpr int kDegrees = 6;
constexpr int kLatLon = 9;
constexpr int kQuaternion = 9;
constexpr int kTime = 9;
constexpr int kLens = 6;

// Rounds to the documented precision; magnitudes where the scaled value would overflow are already
// coarser than that precision and are written as they are.
double R(double v, int decimals) { return std::fabs(v) > 1e15 ? v : RoundToDecimals(v, decimals); }

Json Vec3(const Eigen::Vector3d& v) { return Json::array({R(v.x(), kMetres), R(v.y(), kMetres), R(v.z(), kMetres)}); }

Json Quat(const Eigen::Quaterniond& q_in) {
  // Renormalize only what is not already unit to the written precision, so that reading a plan and
  // writing it again gives the same bytes.
  Eigen::Quaterniond q = q_in;
  if (std::fabs(q.norm() - 1.0) > 1e-8) q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return Json::array({R(q.w(), kQuaternion), R(q.x(), kQuaternion), R(q.y(), kQuaternion), R(q.z(), kQuaternion)});
}

Json Focus(double focus_m) {
  if (std::isinf(focus_m)) return Json(nullptr);
  return Json(R(focus_m, kMetres));
}

Json CameraJson(const CameraSpec& c) {
  Json j = Json::object();
  j["filmback"] = c.filmback;
  j["sensor_width_mm"] = c.sensor_width_mm;
  j["sensor_height_mm"] = c.sensor_height_mm;
  j["width_px"] = c.width_px;
  j["height_px"] = c.height_px;
  j["min_focal_length_mm"] = c.min_focal_length_mm;
  j["max_focal_length_mm"] = c.max_focal_length_mm;
  j["min_f_number"] = c.min_f_number;
  j["max_f_number"] = c.max_f_number;
  j["min_focus_distance_m"] = c.min_focus_distance_m;
  j["coc_mm"] = c.coc_mm;
  j["max_focal_rate_mm_s"] = c.max_focal_rate_mm_s;
  j["max_focus_rate_m_s"] = c.max_focus_rate_m_s;
  j["max_aperture_rate_stops_s"] = c.max_aperture_rate_stops_s;
  return j;
}

// ---- reading -------------------------------------------------------------------------------

// The domains every number read here must lie in (docs/plan-format.md, "Domains"), so that no stage
// computes with a value that overflows, divides by zero or has no thin-lens image (docs/optics.md,
// "Domain of the inputs"). A number outside is refused where it is read, naming its JSON path.
constexpr double kMaxCoordinateM = kMaxEnuCoordinateM;  // positions, heights (core/geodetic_json.h), lengths
constexpr double kMaxTimeS = 1e6;                       // times in [0, 1e6] s (11.6 days)
constexpr double kMinTimeStepS = 1e-6;                  // samples at least 1 us apart (1000 Hz is 1 ms)
constexpr double kMaxAngleDeg = 360;                    // headings and gimbal angles: |v| <= 360 deg
constexpr double kQuaternionTolerance = 1e-3;           // | |q| - 1 | above this is not a rotation
constexpr double kMinFocalLengthMm = 0.1, kMaxFocalLengthMm = 1e5;
constexpr double kMinFNumber = 0.1, kMaxFNumber = 1000;
constexpr double kMinFocusM = 1e-3, kMaxFocusM = 1e7;  // kMaxFocusM: the camera's min_focus_distance_m
constexpr double kInfiniteFocusM = 1e15;               // a focus distance beyond is read as infinity
constexpr double kMinShutterS = 1e-6, kMaxShutterS = 60;
constexpr double kMinCocMm = 1e-4, kMaxCocMm = 10;

// A positive length, count or rate up to the coordinate bound.
double ReadPositive(const JsonField& f) {
  const double v = f.AsPositive();
  if (!(v <= kMaxCoordinateM)) f.Fail("must be in (0, 1e7], got " + FormatSignificant(v));
  return v;
}

double ReadTime(const JsonField& f) { return f.AsDoubleIn(0, kMaxTimeS); }

double ReadAngle(const JsonField& f) { return f.AsDoubleIn(-kMaxAngleDeg, kMaxAngleDeg); }

// Unit norm within kQuaternionTolerance: renormalized (values rounded to 1e-9 stay as written), refused
// beyond it.
Eigen::Quaterniond ReadQuat(const JsonField& f) {
  if (!f.IsArray() || f.size() != 4) f.Fail("expected [w, x, y, z]");
  Eigen::Quaterniond q(f.At(0).AsDouble(), f.At(1).AsDouble(), f.At(2).AsDouble(), f.At(3).AsDouble());
  const double n = q.norm();
  if (!(std::fabs(n - 1.0) <= kQuaternionTolerance)) {
    f.Fail("not a unit quaternion (norm " + FormatSignificant(n) + "; must be within 0.001 of 1)");
  }
  if (std::fabs(n - 1.0) > 1e-8) q.coeffs() /= n;
  return q;
}

double ReadFocalLength(const JsonField& f) { return f.AsDoubleIn(kMinFocalLengthMm, kMaxFocalLengthMm); }
double ReadFNumber(const JsonField& f) { return f.AsDoubleIn(kMinFNumber, kMaxFNumber); }

// Focus distance (null = infinity), beyond the focal length: s <= f has no real image (docs/optics.md).
// Beyond kInfiniteFocusM it is infinity: `plan` interpolates focus in dioptres, so a rack to infinity
// passes through distances as large as the last step's 1/d (1.6e8 m in examples/keyframes_shots.json),
// and no blur differs from infinity's there by 1e-12 px, while a product with such a distance (a ray to
// the plane of focus) would overflow.
double ReadFocus(const JsonField& parent, const char* key, double focal_length_mm) {
  if (!parent.Has(key)) {
    if (!parent.node().contains(key)) parent[key];   // throws "missing"
    return std::numeric_limits<double>::infinity();  // null = infinity
  }
  const JsonField field = parent[key];
  const double s = field.AsDouble();
  if (s > kInfiniteFocusM) return std::numeric_limits<double>::infinity();
  if (!(s >= kMinFocusM)) field.Fail("must be at least 0.001 m (null for infinity), got " + FormatSignificant(s));
  if (!(s * 1e3 > focal_length_mm)) {
    field.Fail(FormatSignificant(s) + " m is inside the focal length " + FormatSignificant(focal_length_mm) +
               " mm (no real image)");
  }
  return s;
}

CameraSpec ReadCamera(const JsonField& f) {
  CameraSpec c;
  c.filmback = f.StringOr("filmback", c.filmback);
  c.sensor_width_mm = f["sensor_width_mm"].AsDoubleIn(0.1, 1000);
  c.sensor_height_mm = f["sensor_height_mm"].AsDoubleIn(0.1, 1000);
  auto pixels = [&](const char* key) {
    const int64_t v = f[key].AsInt();
    if (v <= 0 || v > 100000) f[key].Fail("must be in [1, 100000]");
    return static_cast<int>(v);
  };
  c.width_px = pixels("width_px");
  c.height_px = pixels("height_px");
  c.min_focal_length_mm = ReadFocalLength(f["min_focal_length_mm"]);
  c.max_focal_length_mm = ReadFocalLength(f["max_focal_length_mm"]);
  if (c.max_focal_length_mm < c.min_focal_length_mm) f["max_focal_length_mm"].Fail("must be >= min_focal_length_mm");
  c.min_f_number = ReadFNumber(f["min_f_number"]);
  c.max_f_number = ReadFNumber(f["max_f_number"]);
  if (c.max_f_number < c.min_f_number) f["max_f_number"].Fail("must be >= min_f_number");
  c.min_focus_distance_m = f["min_focus_distance_m"].AsDoubleIn(kMinFocusM, kMaxFocusM);
  if (auto coc = f.Find("coc_mm")) {  // 0 = from the filmback
    c.coc_mm = coc->AsDoubleIn(0, kMaxCocMm);
    if (c.coc_mm != 0 && c.coc_mm < kMinCocMm) coc->Fail("must be 0 (from the filmback) or in [0.0001, 10]");
  }
  if (auto r = f.Find("max_focal_rate_mm_s")) c.max_focal_rate_mm_s = ReadPositive(*r);
  if (auto r = f.Find("max_focus_rate_m_s")) c.max_focus_rate_m_s = ReadPositive(*r);
  if (auto r = f.Find("max_aperture_rate_stops_s")) c.max_aperture_rate_stops_s = ReadPositive(*r);
  return c;
}

// The drone block: the registry's profile of that name with every field the file gives applied, so
// plans written before a field existed read the same limits. A field the block lacks is the profile's,
// and `notes` says so; a block naming no registry profile must give every field (InputError naming the
// first it lacks): there is no profile to take it from, and no default is a safe limit. The team fields
// are only in "cinepath.plan/2" blocks (`team_fields`).
DroneProfile ReadDrone(const JsonField& f, bool team_fields, std::vector<std::string>* notes) {
  if (!f.IsObject()) f.Fail("expected an object");
  const std::string name = f.StringOr("name", DefaultDroneProfile().name);
  const std::optional<DroneProfile> found = FindDroneProfile(name);  // an old name reads as its new one
  if (!f.Has("name")) notes->push_back(Located(f.Where() + ".name", "missing; the profile \"" + name + "\" is used"));
  for (const DroneProfileField& field : DroneProfileFields()) {
    if ((field.team && !team_fields) || f.Has(field.key)) continue;
    const std::string where = f.Where() + "." + field.key;
    if (!found) {
      throw InputError(Located(where, "missing, and \"" + name +
                                          "\" is not a drone profile to take it from (docs/drones.md lists the "
                                          "profiles and the fields)"));
    }
    const double value = field.number ? (*found).*field.number : (*found).*field.integer;
    notes->push_back(Located(
        where, "missing; the profile \"" + found->name + "\"'s value " + FormatSignificant(value) + " is used"));
  }
  DroneProfile d = found.value_or(DroneProfile{});
  ApplyDroneProfileJson(f, &d);
  d.name = found ? found->name : name;
  return d;
}

std::string CsvNumber(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::ostringstream os;
  os.imbue(std::locale::classic());
  os.precision(15);
  os << v;
  return os.str();
}

// Only the keys a shot sets (ShotIntent::empty() shots carry no "intent").
Json IntentJson(const ShotIntent& intent) {
  Json j = Json::object();
  if (!intent.focus.empty()) j["focus"] = intent.focus;
  if (!intent.rack.empty()) {
    Json rack = Json::array();
    for (const RackIntent& r : intent.rack) {
      rack.push_back(Json{{"at_s", r.at_s}, {"duration_s", r.duration_s}, {"subject", r.subject}});
    }
    j["rack"] = rack;
  }
  if (intent.frame_height_fraction) j["frame_height_fraction"] = *intent.frame_height_fraction;
  if (intent.frame_height_fraction_end) j["frame_height_fraction_end"] = *intent.frame_height_fraction_end;
  if (intent.screen_position != Eigen::Vector2d(0.5, 0.5)) {
    j["screen_position"] = Json::array({intent.screen_position.x(), intent.screen_position.y()});
  }
  if (!intent.sharp.empty()) j["sharp"] = intent.sharp;
  if (intent.background_blur_px) j["background_blur_px"] = *intent.background_blur_px;
  if (intent.background_distance_m) j["background_distance_m"] = *intent.background_distance_m;
  if (!intent.hold.empty()) j["hold"] = intent.hold;
  if (intent.max_deviation_m) j["max_deviation_m"] = *intent.max_deviation_m;
  if (intent.retime) j["retime"] = true;
  return j;
}

ShotIntent ReadIntent(const JsonField& f) {
  f.RejectUnknownKeys({"focus", "rack", "frame_height_fraction", "frame_height_fraction_end", "screen_position",
                       "sharp", "background_blur_px", "background_distance_m", "hold", "max_deviation_m", "retime"});
  ShotIntent intent;
  if (auto focus = f.Find("focus")) {
    intent.focus = focus->AsString();
    if (std::find(kFocusModes.begin(), kFocusModes.end(), intent.focus) == kFocusModes.end()) {
      focus->Fail("unknown focus \"" + intent.focus + "\" (follow, fixed, infinity, keys, rack)");
    }
  }
  if (auto rack = f.Find("rack")) {
    if (intent.focus != "rack") rack->Fail("a rack needs \"focus\": \"rack\"");
    for (const auto& e : rack->Elements()) {
      e.RejectUnknownKeys({"at_s", "duration_s", "subject"});
      RackIntent r;
      r.at_s = e["at_s"].AsDoubleIn(0, kMaxTimeS);
      r.duration_s = e["duration_s"].AsDoubleIn(1e-3, kMaxTimeS);
      r.subject = e["subject"].AsString();
      if (!intent.rack.empty() && r.at_s < intent.rack.back().at_s) e["at_s"].Fail("racks must be in time order");
      intent.rack.push_back(r);
    }
  }
  if (f.Has("frame_height_fraction")) intent.frame_height_fraction = ReadPositive(f["frame_height_fraction"]);
  if (f.Has("frame_height_fraction_end"))
    intent.frame_height_fraction_end = ReadPositive(f["frame_height_fraction_end"]);
  if (auto sp = f.Find("screen_position")) {
    if (sp->size() != 2) sp->Fail("expected [x, y]");
    intent.screen_position = {sp->At(0).AsDoubleIn(0, 1), sp->At(1).AsDoubleIn(0, 1)};
  }
  if (auto sharp = f.Find("sharp")) {
    for (const auto& e : sharp->Elements()) intent.sharp.push_back(e.AsString());
  }
  if (f.Has("background_blur_px")) intent.background_blur_px = ReadPositive(f["background_blur_px"]);
  if (f.Has("background_distance_m")) intent.background_distance_m = ReadPositive(f["background_distance_m"]);
  if (auto hold = f.Find("hold")) intent.hold = ReadHoldList(*hold);
  if (f.Has("max_deviation_m")) intent.max_deviation_m = f["max_deviation_m"].AsDoubleIn(0, kMaxCoordinateM);
  if (f.Has("retime")) intent.retime = f["retime"].AsBool();
  return intent;
}

}  // namespace

std::vector<std::string> ReadHoldList(const JsonField& hold) {
  std::vector<std::string> channels;
  for (const auto& e : hold.Elements()) {
    const std::string channel = e.AsString();
    if (std::find(kOptimizeChannels.begin(), kOptimizeChannels.end(), channel) == kOptimizeChannels.end()) {
      e.Fail("unknown channel \"" + channel + "\" (position, orientation, focal_length, focus, aperture)");
    }
    channels.push_back(channel);
  }
  return channels;
}

namespace {

// Everything of a flight after the plan's header (origin, frame rate), appended to `doc` in the order
// version 1 writes it.
void AppendFlightJson(const Trajectory& plan, bool drone_team_fields, Json& doc) {
  doc["camera"] = CameraJson(plan.camera);
  doc["drone"] = DroneProfileToJson(plan.drone, drone_team_fields);

  Json shots = Json::array();
  for (const auto& s : plan.shots) {
    Json j = Json::object();
    j["name"] = s.name;
    j["type"] = s.type;
    j["subject"] = s.subject.empty() ? Json(nullptr) : Json(s.subject);
    j["transition"] = s.transition;
    j["start_time_s"] = R(s.start_time_s, kTime);
    j["end_time_s"] = R(s.end_time_s, kTime);
    if (!s.intent.empty()) j["intent"] = IntentJson(s.intent);
    shots.push_back(std::move(j));
  }
  doc["shots"] = std::move(shots);

  Json subjects = Json::array();
  for (const auto& s : plan.subjects) {
    Json j = Json::object();
    j["name"] = s.name;
    j["height_m"] = s.height_m;
    Json positions = Json::array();
    for (const auto& p : s.positions_enu_m) positions.push_back(Vec3(p));
    j["positions_enu_m"] = std::move(positions);
    subjects.push_back(std::move(j));
  }
  doc["subjects"] = std::move(subjects);

  Json keys = Json::array();
  for (const auto& k : plan.keyframes) {
    Json j = Json::object();
    j["shot"] = k.shot;
    j["time_s"] = R(k.time_s, kTime);
    j["position_enu_m"] = Vec3(k.position_enu_m);
    j["world_from_camera"] = Quat(k.world_from_camera);
    j["focal_length_mm"] = R(k.focal_length_mm, kLens);
    j["focus_distance_m"] = Focus(k.focus_distance_m);
    j["f_number"] = R(k.f_number, kLens);
    keys.push_back(std::move(j));
  }
  doc["keyframes"] = std::move(keys);

  Json samples = Json::array();
  for (const auto& s : plan.samples) {
    Json j = Json::object();
    j["time_s"] = R(s.time_s, kTime);
    j["position_enu_m"] = Vec3(s.position_enu_m);
    if (plan.origin) {
      j["lat_deg"] = R(s.geodetic.lat_deg, kLatLon);
      j["lon_deg"] = R(s.geodetic.lon_deg, kLatLon);
      j["height_m"] = R(s.geodetic.height_m, kMetres);
    }
    j["world_from_camera"] = Quat(s.world_from_camera);
    j["drone_heading_deg"] = R(s.drone_heading_deg, kDegrees);
    j["gimbal_pitch_deg"] = R(s.gimbal_pitch_deg, kDegrees);
    j["gimbal_roll_deg"] = R(s.gimbal_roll_deg, kDegrees);
    j["gimbal_yaw_deg"] = R(s.gimbal_yaw_deg, kDegrees);
    j["focal_length_mm"] = R(s.focal_length_mm, kLens);
    j["focus_distance_m"] = Focus(s.focus_distance_m);
    j["f_number"] = R(s.f_number, kLens);
    j["shutter_s"] = R(s.shutter_s, kTime);
    j["shot"] = s.shot;
    j["subjects_in_frame"] = s.subjects_in_frame;
    samples.push_back(std::move(j));
  }
  doc["samples"] = std::move(samples);

  Json report = Json::object();
  report["feasible"] = plan.feasibility.feasible();
  Json violations = Json::array();
  for (const auto& v : plan.feasibility.violations) {
    Json j = Json::object();
    j["limit"] = v.limit;
    j["shot"] = v.shot;
    j["start_time_s"] = R(v.start_time_s, kTime);
    j["end_time_s"] = R(v.end_time_s, kTime);
    j["worst_value"] = R(v.worst_value, kLens);
    j["limit_value"] = R(v.limit_value, kLens);
    j["unit"] = v.unit;
    violations.push_back(std::move(j));
  }
  report["violations"] = std::move(violations);
  report["skipped"] = plan.feasibility.skipped;
  doc["feasibility"] = std::move(report);
  if (!plan.optimized.is_null()) doc["optimized"] = plan.optimized;
}

}  // namespace

Json PlanToJson(const Trajectory& plan) {
  Json doc = Json::object();
  doc["schema"] = kPlanSchema;
  doc["generator"] = std::string("cinepath ") + kVersion;
  doc["origin"] = plan.origin ? GeodeticToJson(*plan.origin) : Json(nullptr);
  doc["frame_rate_hz"] = plan.frame_rate_hz;
  AppendFlightJson(plan, false, doc);
  return doc;
}

std::string PlanToText(const Trajectory& plan) { return DumpJson(PlanToJson(plan)); }

namespace {

// A flight's keys after the header (camera, drone, shots, samples, ...), into `plan` (origin and frame
// rate already set).
// One element of "samples"; `previous` (null for the first) for the order of times.
TrajectorySample ReadSample(const JsonField& f, const TrajectorySample* previous, bool geodetic) {
  TrajectorySample s;
  s.time_s = ReadTime(f["time_s"]);
  if (previous && !(s.time_s - previous->time_s >= kMinTimeStepS)) {
    f["time_s"].Fail("times must increase (by at least 1e-6 s)");
  }
  s.position_enu_m = EnuPositionFromJson(f["position_enu_m"]);
  if (geodetic) {
    s.geodetic.lat_deg = f["lat_deg"].AsDoubleIn(-90, 90);
    s.geodetic.lon_deg = f["lon_deg"].AsDoubleIn(-180, 180);
    s.geodetic.height_m = EnuCoordinateFromJson(f["height_m"]);
  }
  s.world_from_camera = ReadQuat(f["world_from_camera"]);
  s.drone_heading_deg = ReadAngle(f["drone_heading_deg"]);
  s.gimbal_pitch_deg = ReadAngle(f["gimbal_pitch_deg"]);
  if (auto a = f.Find("gimbal_roll_deg")) s.gimbal_roll_deg = ReadAngle(*a);
  if (auto a = f.Find("gimbal_yaw_deg")) s.gimbal_yaw_deg = ReadAngle(*a);
  s.focal_length_mm = ReadFocalLength(f["focal_length_mm"]);
  s.focus_distance_m = ReadFocus(f, "focus_distance_m", s.focal_length_mm);
  s.f_number = ReadFNumber(f["f_number"]);
  s.shutter_s = f["shutter_s"].AsDoubleIn(kMinShutterS, kMaxShutterS);
  s.shot = f.StringOr("shot", "");
  if (auto subj = f.Find("subjects_in_frame")) {
    for (const auto& e : subj->Elements()) s.subjects_in_frame.push_back(e.AsString());
  }
  return s;
}

void ReadShotSpans(const JsonField& root, Trajectory& plan) {
  for (const auto& f : root["shots"].Elements()) {
    ShotSpan s;
    s.name = f["name"].AsString();
    s.type = f["type"].AsString();
    if (auto subj = f.Find("subject")) s.subject = subj->AsString();
    s.transition = f.StringOr("transition", "continuous");
    s.start_time_s = ReadTime(f["start_time_s"]);
    s.end_time_s = ReadTime(f["end_time_s"]);
    if (s.end_time_s < s.start_time_s) f["end_time_s"].Fail("must be >= start_time_s");
    if (auto intent = f.Find("intent")) s.intent = ReadIntent(*intent);
    plan.shots.push_back(std::move(s));
  }
}

// "subjects", "keyframes": each optional.
void ReadSubjectsAndKeyframes(const JsonField& root, Trajectory& plan) {
  if (auto subjects = root.Find("subjects")) {
    for (const auto& f : subjects->Elements()) {
      SubjectTrack t;
      t.name = f["name"].AsString();
      t.height_m = ReadPositive(f["height_m"]);
      const auto positions = f["positions_enu_m"];
      if (positions.size() != plan.samples.size()) {
        positions.Fail("expected one position per sample (" + std::to_string(plan.samples.size()) + ")");
      }
      for (const auto& p : positions.Elements()) t.positions_enu_m.push_back(EnuPositionFromJson(p));
      plan.subjects.push_back(std::move(t));
    }
  }

  if (auto keys = root.Find("keyframes")) {
    for (const auto& f : keys->Elements()) {
      Keyframe k;
      k.shot = f.StringOr("shot", "");
      k.time_s = ReadTime(f["time_s"]);
      k.position_enu_m = EnuPositionFromJson(f["position_enu_m"]);
      k.world_from_camera = ReadQuat(f["world_from_camera"]);
      k.focal_length_mm = ReadFocalLength(f["focal_length_mm"]);
      k.focus_distance_m = ReadFocus(f, "focus_distance_m", k.focal_length_mm);
      k.f_number = ReadFNumber(f["f_number"]);
      plan.keyframes.push_back(std::move(k));
    }
  }
}

// "feasibility" as the plan was written (the report of the stage that wrote it).
void ReadFeasibility(const JsonField& root, Trajectory& plan) {
  if (auto report = root.Find("feasibility")) {
    for (const auto& f : (*report)["violations"].Elements()) {
      FeasibilityViolation v;
      v.limit = f["limit"].AsString();
      v.shot = f.StringOr("shot", "");
      v.start_time_s = f["start_time_s"].AsDouble();
      v.end_time_s = f["end_time_s"].AsDouble();
      v.worst_value = f["worst_value"].AsDouble();
      v.limit_value = f["limit_value"].AsDouble();
      v.unit = f.StringOr("unit", "");
      plan.feasibility.violations.push_back(std::move(v));
    }
    if (auto skipped = report->Find("skipped")) {
      for (const auto& e : skipped->Elements()) plan.feasibility.skipped.push_back(e.AsString());
    }
  }
}

void ReadFlight(const JsonField& root, bool team_fields, Trajectory& plan) {
  plan.camera = ReadCamera(root["camera"]);
  if (auto d = root.Find("drone")) {
    plan.drone = ReadDrone(*d, team_fields, &plan.notes);
  } else {
    plan.drone = DefaultDroneProfile();
    const std::string where = Located(root.source(), root.path().empty() ? "drone" : root.path() + ".drone");
    plan.notes.push_back(Located(where, "missing; the profile \"" + plan.drone.name + "\" is used"));
  }
  ReadShotSpans(root, plan);
  const JsonField samples_field = root["samples"];
  const auto samples = samples_field.Elements();
  if (samples.empty()) samples_field.Fail("must hold at least one sample");
  plan.samples.reserve(samples.size());
  for (const auto& f : samples) {
    plan.samples.push_back(
        ReadSample(f, plan.samples.empty() ? nullptr : &plan.samples.back(), plan.origin.has_value()));
  }
  ReadSubjectsAndKeyframes(root, plan);
  ReadFeasibility(root, plan);
  if (auto optimized = root.Find("optimized")) {
    if (!optimized->IsObject() && !optimized->IsNull()) optimized->Fail("expected an object");
    plan.optimized = optimized->node();
  }
}

}  // namespace

Trajectory PlanFromJson(const Json& document, const std::string& source) {
  const JsonField root(document, source);
  if (!root.IsObject()) root.Fail("expected a cinepath plan (a JSON object)");
  const std::string schema = root["schema"].AsString();
  if (schema == kTeamPlanSchema) {
    root["schema"].Fail("this plan holds several drones (\"" + schema + "\"); this step reads one flight (\"" +
                        kPlanSchema + "\")");
  }
  if (schema != kPlanSchema) {
    root["schema"].Fail("unsupported plan version \"" + schema + "\" (this cinepath reads \"" + kPlanSchema +
                        "\" and \"" + kTeamPlanSchema + "\")");
  }
  Trajectory plan;
  if (auto o = root.Find("origin")) plan.origin = GeodeticFromJson(*o);
  plan.frame_rate_hz = root["frame_rate_hz"].AsDoubleIn(0.01, 1000);
  ReadFlight(root, false, plan);
  return plan;
}

Trajectory ReadPlanFile(const std::filesystem::path& path) { return PlanFromJson(ParseJsonFile(path), path.string()); }

namespace {

Json ConflictJson(const TeamConflict& c) {
  Json j = Json::object();
  j["limit"] = c.limit;
  j["drone"] = c.drone;
  j["other"] = c.other;
  j["start_time_s"] = R(c.start_time_s, kTime);
  j["end_time_s"] = R(c.end_time_s, kTime);
  j["worst_value"] = R(c.worst_value, kLens);
  j["limit_value"] = R(c.limit_value, kLens);
  j["unit"] = c.unit;
  return j;
}

}  // namespace

Json TeamPlanToJson(const TeamPlan& plan) {
  if (plan.single) {
    if (plan.flights.size() != 1) throw std::logic_error("TeamPlanToJson: a version 1 plan holds one flight");
    return PlanToJson(plan.flights[0].plan);
  }
  Json doc = Json::object();
  doc["schema"] = kTeamPlanSchema;
  doc["generator"] = std::string("cinepath ") + kVersion;
  doc["origin"] = plan.origin ? GeodeticToJson(*plan.origin) : Json(nullptr);
  doc["frame_rate_hz"] = plan.frame_rate_hz;
  Json edit = Json::array();
  for (const auto& cut : plan.edit) {
    Json j = Json::object();
    j["at_s"] = R(cut.at_s, kTime);
    j["drone"] = cut.drone;
    if (cut.match_focus) j["match_focus"] = true;
    edit.push_back(std::move(j));
  }
  doc["edit"] = std::move(edit);

  Json team = Json::object();
  team["clear"] = plan.team.clear();
  team["min_separation_m"] = R(plan.team.min_separation_m, kMetres);
  Json conflicts = Json::array();
  for (const auto& c : plan.team.conflicts) conflicts.push_back(ConflictJson(c));
  team["conflicts"] = std::move(conflicts);
  Json matches = Json::array();
  for (const auto& m : plan.team.focus_matches) {
    Json j = Json::object();
    j["at_s"] = R(m.at_s, kTime);
    j["from_drone"] = m.from_drone;
    j["to_drone"] = m.to_drone;
    j["subject"] = m.subject;
    j["from_focus_error_dioptres"] = R(m.from_focus_error_dioptres, kLens);
    j["to_focus_error_dioptres"] = R(m.to_focus_error_dioptres, kLens);
    matches.push_back(std::move(j));
  }
  team["focus_matches"] = std::move(matches);
  doc["team"] = std::move(team);
  if (!plan.optimized.is_null()) doc["optimized"] = plan.optimized;

  Json flights = Json::array();
  for (const auto& f : plan.flights) {
    Json j = Json::object();
    j["name"] = f.name;
    j["home_enu_m"] = f.home_enu_m ? Vec3(*f.home_enu_m) : Json(nullptr);
    AppendFlightJson(f.plan, true, j);
    flights.push_back(std::move(j));
  }
  doc["flights"] = std::move(flights);
  return doc;
}

std::string TeamPlanToText(const TeamPlan& plan) { return DumpJson(TeamPlanToJson(plan)); }

TeamPlan TeamPlanFromJson(const Json& document, const std::string& source) {
  const JsonField root(document, source);
  if (!root.IsObject()) root.Fail("expected a cinepath plan (a JSON object)");
  TeamPlan team;
  if (root["schema"].AsString() == kPlanSchema) {
    Trajectory single = PlanFromJson(document, source);
    team.origin = single.origin;
    team.frame_rate_hz = single.frame_rate_hz;
    team.single = true;
    team.team.min_separation_m = single.drone.min_separation_m;
    team.flights.push_back({single.drone.name, std::nullopt, std::move(single)});
    return team;
  }
  const std::string schema = root["schema"].AsString();
  if (schema != kTeamPlanSchema) {
    root["schema"].Fail("unsupported plan version \"" + schema + "\" (this cinepath reads \"" + kPlanSchema +
                        "\" and \"" + kTeamPlanSchema + "\")");
  }
  if (auto o = root.Find("origin")) team.origin = GeodeticFromJson(*o);
  team.frame_rate_hz = root["frame_rate_hz"].AsDoubleIn(0.01, 1000);
  const JsonField flights = root["flights"];
  if (flights.size() == 0) flights.Fail("must hold at least one flight");
  for (const auto& f : flights.Elements()) {
    DroneFlight flight;
    flight.name = f["name"].AsString();
    if (flight.name.empty()) f["name"].Fail("must not be empty");
    if (team.FindFlight(flight.name) >= 0) f["name"].Fail("duplicate drone name \"" + flight.name + "\"");
    if (auto h = f.Find("home_enu_m")) flight.home_enu_m = EnuPositionFromJson(*h);
    flight.plan.origin = team.origin;
    flight.plan.frame_rate_hz = team.frame_rate_hz;
    ReadFlight(f, true, flight.plan);
    team.flights.push_back(std::move(flight));
  }
  if (auto edit = root.Find("edit")) {
    for (const auto& e : edit->Elements()) {
      EditCut cut;
      cut.at_s = ReadTime(e["at_s"]);
      cut.drone = e["drone"].AsString();
      cut.match_focus = e.BoolOr("match_focus", false);
      if (team.FindFlight(cut.drone) < 0) e["drone"].Fail("no flight is named \"" + cut.drone + "\"");
      if (!team.edit.empty() && !(cut.at_s > team.edit.back().at_s)) e["at_s"].Fail("cuts must be in increasing time");
      team.edit.push_back(std::move(cut));
    }
  }
  if (auto t = root.Find("team")) {
    if (auto m = t->Find("min_separation_m")) team.team.min_separation_m = m->AsDoubleIn(0, kMaxCoordinateM);
    if (auto conflicts = t->Find("conflicts")) {
      for (const auto& f : conflicts->Elements()) {
        TeamConflict c;
        c.limit = f["limit"].AsString();
        c.drone = f["drone"].AsString();
        c.other = f["other"].AsString();
        c.start_time_s = f["start_time_s"].AsDouble();
        c.end_time_s = f["end_time_s"].AsDouble();
        c.worst_value = f["worst_value"].AsDouble();
        c.limit_value = f["limit_value"].AsDouble();
        c.unit = f.StringOr("unit", "");
        team.team.conflicts.push_back(std::move(c));
      }
    }
    if (auto matches = t->Find("focus_matches")) {
      for (const auto& f : matches->Elements()) {
        FocusMatch m;
        m.at_s = f["at_s"].AsDouble();
        m.from_drone = f["from_drone"].AsString();
        m.to_drone = f["to_drone"].AsString();
        m.subject = f["subject"].AsString();
        m.from_focus_error_dioptres = f["from_focus_error_dioptres"].AsDouble();
        m.to_focus_error_dioptres = f["to_focus_error_dioptres"].AsDouble();
        team.team.focus_matches.push_back(std::move(m));
      }
    }
  }
  if (auto optimized = root.Find("optimized")) {
    if (!optimized->IsObject() && !optimized->IsNull()) optimized->Fail("expected an object");
    team.optimized = optimized->node();
  }
  return team;
}

TeamPlan ReadTeamPlanFile(const std::filesystem::path& path) {
  return TeamPlanFromJson(ParseJsonFile(path), path.string());
}

std::vector<std::string> TeamPlanNotes(const TeamPlan& plan) {
  std::vector<std::string> notes;
  for (const auto& flight : plan.flights) notes.insert(notes.end(), flight.plan.notes.begin(), flight.plan.notes.end());
  return notes;
}

std::string PlanSamplesToCsv(const Trajectory& plan) {
  std::string out =
      "time_s,shot,east_m,north_m,up_m,lat_deg,lon_deg,height_m,qw,qx,qy,qz,drone_heading_deg,"
      "gimbal_pitch_deg,gimbal_roll_deg,gimbal_yaw_deg,focal_length_mm,focus_distance_m,f_number,shutter_s,"
      "subjects_in_frame\n";
  auto num = [](double v, int decimals) { return CsvNumber(std::isinf(v) ? v : RoundToDecimals(v, decimals)); };
  for (const auto& s : plan.samples) {
    Eigen::Quaterniond q = s.world_from_camera.normalized();
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    std::string subjects;
    for (size_t i = 0; i < s.subjects_in_frame.size(); ++i) {
      if (i) subjects += ';';
      subjects += s.subjects_in_frame[i];
    }
    const std::string geo_lat = plan.origin ? num(s.geodetic.lat_deg, kLatLon) : "";
    const std::string geo_lon = plan.origin ? num(s.geodetic.lon_deg, kLatLon) : "";
    const std::string geo_h = plan.origin ? num(s.geodetic.height_m, kMetres) : "";
    out += num(s.time_s, kTime) + "," + s.shot + "," + num(s.position_enu_m.x(), kMetres) + "," +
           num(s.position_enu_m.y(), kMetres) + "," + num(s.position_enu_m.z(), kMetres) + "," + geo_lat + "," +
           geo_lon + "," + geo_h + "," + num(q.w(), kQuaternion) + "," + num(q.x(), kQuaternion) + "," +
           num(q.y(), kQuaternion) + "," + num(q.z(), kQuaternion) + "," + num(s.drone_heading_deg, kDegrees) + "," +
           num(s.gimbal_pitch_deg, kDegrees) + "," + num(s.gimbal_roll_deg, kDegrees) + "," +
           num(s.gimbal_yaw_deg, kDegrees) + "," + num(s.focal_length_mm, kLens) + "," +
           num(s.focus_distance_m, kMetres) + "," + num(s.f_number, kLens) + "," + num(s.shutter_s, kTime) + "," +
           subjects + "\n";
  }
  return out;
}

}  // namespace cinepath

namespace cinepath {

std::string TeamPlanSamplesToCsv(const TeamPlan& plan) {
  if (plan.single) return PlanSamplesToCsv(plan.flights.at(0).plan);
  std::string out;
  for (size_t i = 0; i < plan.flights.size(); ++i) {
    const std::string csv = PlanSamplesToCsv(plan.flights[i].plan);
    size_t line_start = 0;
    bool header = true;
    while (line_start < csv.size()) {
      const size_t end = csv.find('\n', line_start);
      const std::string line = csv.substr(line_start, end == std::string::npos ? std::string::npos : end - line_start);
      line_start = end == std::string::npos ? csv.size() : end + 1;
      if (header) {
        if (i == 0) out += "drone," + line + "\n";
        header = false;
        continue;
      }
      out += plan.flights[i].name + "," + line + "\n";
    }
  }
  return out;
}

}  // namespace cinepath
