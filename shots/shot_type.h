// The shot types a shot list can ask for, and their names in shots.json.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace cinepath::shots {

enum class ShotType {
  kChase,      // behind the subject at a distance, height and lateral offset, with lag
  kOrbit,      // circle the subject: radius, height, turns or angular speed, direction, start bearing
  kFlyby,      // straight pass at a closest-approach distance; the camera pans to hold the subject
  kDolly,      // DOLLY / TRACK: parallel to the subject's motion (or along a bearing for a still one)
  kCrane,      // CRANE / REVEAL: rise (and optionally tilt up from a start pitch) while framing
  kHelix,      // orbit + climb (radius and height ramp)
  kDronie,     // away and up, looking back at the subject
  kTopDown,    // nadir view above the subject
  kDollyZoom,  // distance changes while the focal length keeps the subject's image size
  kLockedOff,  // a still camera
  kKeyframes,  // free keyframes (positions, orientations, lens values)
};

std::string_view ShotTypeName(ShotType t);  // canonical: "CHASE", "ORBIT", ..., "KEYFRAMES"
// Accepts the canonical names and the aliases TRACK, REVEAL, TOP_DOWN, DOLLY_ZOOM, LOCKED_OFF, FREE.
std::optional<ShotType> ShotTypeFromName(std::string_view name);
const std::vector<std::string_view>& ShotTypeNames();

}  // namespace cinepath::shots
