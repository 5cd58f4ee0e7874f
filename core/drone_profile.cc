#include "core/drone_profile.h"

#include <algorithm>
#include <cmath>

namespace cinepath {

const std::vector<DroneProfileField>& DroneProfileFields() {
  using C = DroneProfileField::Check;
  using D = DroneProfile;
  static const std::vector<DroneProfileField> fields = {
      {.key = "max_horizontal_speed_m_s", .number = &D::max_horizontal_speed_m_s},
      {.key = "max_climb_rate_m_s", .number = &D::max_climb_rate_m_s},
      {.key = "max_descent_rate_m_s", .number = &D::max_descent_rate_m_s},
      {.key = "max_acceleration_m_s2", .number = &D::max_acceleration_m_s2},
      {.key = "max_jerk_m_s3", .number = &D::max_jerk_m_s3},
      {.key = "max_yaw_rate_deg_s", .number = &D::max_yaw_rate_deg_s},
      {.key = "min_gimbal_pitch_deg", .number = &D::min_gimbal_pitch_deg, .check = C::kAny},
      {.key = "max_gimbal_pitch_deg", .number = &D::max_gimbal_pitch_deg, .check = C::kAny},
      {.key = "max_gimbal_pitch_rate_deg_s", .number = &D::max_gimbal_pitch_rate_deg_s},
      {.key = "min_altitude_m", .number = &D::min_altitude_m, .check = C::kAny},
      {.key = "max_altitude_m", .number = &D::max_altitude_m, .check = C::kAny},
      {.key = "min_subject_distance_m", .number = &D::min_subject_distance_m, .check = C::kNonNegative},
      {.key = "min_terrain_clearance_m", .number = &D::min_terrain_clearance_m, .check = C::kNonNegative},
      {.key = "min_relative_altitude_m", .number = &D::min_relative_altitude_m, .check = C::kAny},
      {.key = "max_relative_altitude_m", .number = &D::max_relative_altitude_m, .check = C::kAny},
      {.key = "max_mission_items", .integer = &D::max_mission_items},
      {.key = "dji_drone_enum", .integer = &D::dji_drone_enum, .check = C::kNonNegative},
      {.key = "dji_drone_sub_enum", .integer = &D::dji_drone_sub_enum, .check = C::kNonNegative},
      {.key = "dji_payload_enum", .integer = &D::dji_payload_enum, .check = C::kNonNegative},
      {.key = "body_radius_m", .number = &D::body_radius_m, .team = true},
      {.key = "min_separation_m", .number = &D::min_separation_m, .check = C::kNonNegative, .team = true},
  };
  return fields;
}

Json DroneProfileToJson(const DroneProfile& profile, bool team_fields) {
  Json j = Json::object();
  j["name"] = profile.name;
  if (!profile.firmware.empty()) j["firmware"] = profile.firmware;
  for (const DroneProfileField& f : DroneProfileFields()) {
    if (f.team && !team_fields) continue;
    if (f.number) {
      j[f.key] = profile.*f.number;
    } else {
      j[f.key] = profile.*f.integer;
    }
  }
  if (profile.lens) {
    j["lens"] = {{"min_focal_length_mm", profile.lens->min_focal_length_mm},
                 {"max_focal_length_mm", profile.lens->max_focal_length_mm},
                 {"min_f_number", profile.lens->min_f_number},
                 {"max_f_number", profile.lens->max_f_number},
                 {"min_focus_distance_m", profile.lens->min_focus_distance_m}};
  }
  return j;
}

namespace {

// Every limit is metres, seconds or degrees of one aircraft: beyond 1e7 in magnitude, or a positive limit
// (a divisor) under 1e-6, a value only overflows the costs and rates computed with it (docs/drones.md).
constexpr double kMaxProfileValue = 1e7;
constexpr double kMinPositiveProfileValue = 1e-6;

FixedLens ReadLens(const JsonField& f) {
  f.RejectUnknownKeys(
      {"min_focal_length_mm", "max_focal_length_mm", "min_f_number", "max_f_number", "min_focus_distance_m"});
  FixedLens lens;
  // The ranges plan.json's camera block allows (docs/optics.md, "Domain of the inputs").
  lens.min_focal_length_mm = f["min_focal_length_mm"].AsDoubleIn(0.1, 1e5);
  lens.max_focal_length_mm = f["max_focal_length_mm"].AsDoubleIn(0.1, 1e5);
  lens.min_f_number = f["min_f_number"].AsDoubleIn(0.1, 1000);
  lens.max_f_number = f["max_f_number"].AsDoubleIn(0.1, 1000);
  lens.min_focus_distance_m = f["min_focus_distance_m"].AsDoubleIn(1e-3, 1e7);
  if (lens.max_focal_length_mm < lens.min_focal_length_mm)
    f["max_focal_length_mm"].Fail("must be >= min_focal_length_mm");
  if (lens.max_f_number < lens.min_f_number) f["max_f_number"].Fail("must be >= min_f_number");
  return lens;
}

}  // namespace

void ApplyDroneProfileJson(const JsonField& object, DroneProfile* profile,
                           const std::vector<std::string>& allowed_extra) {
  if (!object.IsObject()) object.Fail("expected an object");
  for (const auto& item : object.node().items()) {
    const std::string& key = item.key();
    const bool known = key == "name" || key == "firmware" || key == "lens" ||
                       std::find(allowed_extra.begin(), allowed_extra.end(), key) != allowed_extra.end() ||
                       std::any_of(DroneProfileFields().begin(), DroneProfileFields().end(),
                                   [&](const DroneProfileField& f) { return key == f.key; });
    if (!known) object[key].Fail("unknown key in a drone profile (docs/drones.md lists the fields)");
  }
  if (auto name = object.Find("name")) profile->name = name->AsString();
  if (auto firmware = object.Find("firmware")) {
    const std::string fw = firmware->AsString();
    if (fw != "px4" && fw != "ardupilot" && fw != "dji") firmware->Fail("expected \"px4\", \"ardupilot\" or \"dji\"");
    profile->firmware = fw;
  }
  for (const DroneProfileField& f : DroneProfileFields()) {
    const auto field = object.Find(f.key);
    if (!field) continue;
    using C = DroneProfileField::Check;
    if (f.number) {
      const double v = f.check == C::kPositive      ? field->AsPositive()
                       : f.check == C::kNonNegative ? field->AsNonNegative()
                                                    : field->AsDouble();
      if (!(std::fabs(v) <= kMaxProfileValue)) field->Fail("must lie within [-1e7, 1e7]");
      if (f.check == C::kPositive && !(v >= kMinPositiveProfileValue)) field->Fail("must be at least 1e-6");
      profile->*f.number = v;
    } else {
      const int64_t v = field->AsInt();
      if (v < (f.check == C::kPositive ? 1 : 0) || v > 1'000'000) field->Fail("out of range");
      profile->*f.integer = static_cast<int>(v);
    }
  }
  if (auto lens = object.Find("lens")) profile->lens = ReadLens(*lens);
  auto band = [&](const char* max_key, double min_v, double max_v, const char* what) {
    if (!(max_v > min_v)) {
      if (object.Has(max_key)) object[max_key].Fail(std::string("must be > ") + what);
      object.Fail(std::string(max_key) + " must be > " + what);
    }
  };
  band("max_altitude_m", profile->min_altitude_m, profile->max_altitude_m, "min_altitude_m");
  band("max_relative_altitude_m", profile->min_relative_altitude_m, profile->max_relative_altitude_m,
       "min_relative_altitude_m");
  if (profile->max_gimbal_pitch_deg < profile->min_gimbal_pitch_deg) {
    if (object.Has("max_gimbal_pitch_deg")) object["max_gimbal_pitch_deg"].Fail("must be >= min_gimbal_pitch_deg");
    object.Fail("max_gimbal_pitch_deg must be >= min_gimbal_pitch_deg");
  }
}

}  // namespace cinepath
