// The registry of drone profiles: one naming scheme for shots.json ("drone"), plan.json's drone block,
// `export --drone` and `optimize`. Every figure's source is given beside it in drone_profiles.cc and
// in the table of docs/drones.md.
//
//   px4-multirotor    PX4 multicopter defaults (alias: px4_default_quad, the name before 2026-11)
//   ardupilot-copter  ArduCopter defaults
//   dji-m30           DJI Matrice 30 in a DJI mission (WPML / MSDK)
//   dji-mini4pro      DJI Mini 4 Pro in a DJI mission; fixed 24 mm-equivalent f/1.7 lens
//
// The old name "dji_class" is refused with a message naming dji-m30 and dji-mini4pro: its limits
// (MSDK v4 waypoint ranges) were not one aircraft's.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/drone_profile.h"

namespace cinepath {

const std::vector<DroneProfile>& DroneProfiles();  // in the order docs/drones.md lists them
std::vector<std::string> DroneProfileNames();
const DroneProfile& DefaultDroneProfile();  // px4-multirotor

// By name or alias (an alias gives the profile under its current name); nullopt when unknown.
std::optional<DroneProfile> FindDroneProfile(std::string_view name);
// As FindDroneProfile, but InputError("<where>: ...") listing the known names, or naming the profile
// that replaced an old name.
DroneProfile RequireDroneProfile(std::string_view name, const std::string& where);

}  // namespace cinepath
