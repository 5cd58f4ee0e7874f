// A drone profile: everything cinepath knows about one aircraft, in one place. `plan` checks a flight
// against its flight and gimbal limits, `optimize` keeps to them, and `export` checks the mission
// against its mission limits. The shipped profiles and the sources of their figures are in
// core/drone_profiles.h and docs/drones.md.
//
// Units are in the names. Rates are magnitudes. `min_altitude_m`/`max_altitude_m` bound the plan's
// ENU z (metres above the scene origin); `min/max_relative_altitude_m` bound what the autopilot or app
// accepts in a mission, relative to the take-off point.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/json.h"

namespace cinepath {

// A lens built into the aircraft whose ranges a plan's camera must stay within (a fixed aperture, a
// prime): the camera block of a shot list is checked against it.
struct FixedLens {
  double min_focal_length_mm = 0;
  double max_focal_length_mm = 0;
  double min_f_number = 0;
  double max_f_number = 0;
  double min_focus_distance_m = 0;
};

struct DroneProfile {
  std::string name = "custom";  // the registry name, or "custom"
  std::string firmware;         // what flies it: "px4", "ardupilot" or "dji" ("" for a custom profile)

  // Flight limits.
  double max_horizontal_speed_m_s = 12;
  double max_climb_rate_m_s = 3;
  double max_descent_rate_m_s = 1.5;
  double max_acceleration_m_s2 = 5;
  double max_jerk_m_s3 = 4;
  double max_yaw_rate_deg_s = 45;
  // Gimbal: pitch relative to the horizon, 0 level, -90 straight down.
  double min_gimbal_pitch_deg = -90;
  double max_gimbal_pitch_deg = 30;
  double max_gimbal_pitch_rate_deg_s = 90;
  // The plan's altitude band (ENU z) and the keep-out radius around every subject.
  double min_altitude_m = 1;
  double max_altitude_m = 120;
  double min_subject_distance_m = 2;
  double min_terrain_clearance_m = 3;  // above the scene's mesh (plan --scene), at every sample

  // Mission limits.
  double min_relative_altitude_m = -200;
  double max_relative_altitude_m = 500;
  int max_mission_items = 2000;  // MAVLink items the flight controller stores
  int dji_drone_enum = 67;       // WPML droneInfo / payloadInfo (DJI only)
  int dji_drone_sub_enum = 0;
  int dji_payload_enum = 52;
  // Several drones in one plan (core/team_plan.h): the aircraft as a sphere (propeller tips included),
  // for "no drone in another's shot", and the least distance between any two drones' centres.
  double body_radius_m = 0.4;
  double min_separation_m = 5;

  std::optional<FixedLens> lens;  // a built-in lens, when the aircraft has one
};

// One numeric field of DroneProfile: its JSON key (the member's name), how it is checked, and where it
// lives. Every reader and writer of a profile walks this one table.
struct DroneProfileField {
  enum class Check { kPositive, kNonNegative, kAny };
  const char* key;
  double DroneProfile::*number = nullptr;  // set for real-valued fields
  int DroneProfile::*integer = nullptr;    // set for integer fields
  Check check = Check::kPositive;
  bool team = false;  // only meaningful with several drones: written in "cinepath.plan/2" plans only
};
const std::vector<DroneProfileField>& DroneProfileFields();

// {"name", "firmware" (unless empty), <every field>, "lens" (when present)}, in the table's order. The
// team fields only with `team_fields` (a one-drone plan reads and writes as it did before they existed).
Json DroneProfileToJson(const DroneProfile& profile, bool team_fields = false);

// Applies the fields present in `object` to `profile` (unknown keys other than `allowed_extra` are
// refused) and checks the bands (max > min). InputError names the key.
void ApplyDroneProfileJson(const JsonField& object, DroneProfile* profile,
                           const std::vector<std::string>& allowed_extra = {});

}  // namespace cinepath
