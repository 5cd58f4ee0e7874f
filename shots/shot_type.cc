#include "shots/shot_type.h"

namespace cinepath::shots {
namespace {

struct Entry {
  ShotType type;
  std::string_view name;
};
constexpr Entry kCanonical[] = {
    {ShotType::kChase, "CHASE"},          {ShotType::kOrbit, "ORBIT"},         {ShotType::kFlyby, "FLYBY"},
    {ShotType::kDolly, "DOLLY"},          {ShotType::kCrane, "CRANE"},         {ShotType::kHelix, "HELIX"},
    {ShotType::kDronie, "DRONIE"},        {ShotType::kTopDown, "TOP-DOWN"},    {ShotType::kDollyZoom, "DOLLY-ZOOM"},
    {ShotType::kLockedOff, "LOCKED-OFF"}, {ShotType::kKeyframes, "KEYFRAMES"},
};
constexpr Entry kAliases[] = {
    {ShotType::kDolly, "TRACK"},          {ShotType::kCrane, "REVEAL"},         {ShotType::kTopDown, "TOP_DOWN"},
    {ShotType::kDollyZoom, "DOLLY_ZOOM"}, {ShotType::kLockedOff, "LOCKED_OFF"}, {ShotType::kKeyframes, "FREE"},
};

}  // namespace

std::string_view ShotTypeName(ShotType t) {
  for (const auto& e : kCanonical) {
    if (e.type == t) return e.name;
  }
  return "KEYFRAMES";
}

std::optional<ShotType> ShotTypeFromName(std::string_view name) {
  for (const auto& e : kCanonical) {
    if (e.name == name) return e.type;
  }
  for (const auto& e : kAliases) {
    if (e.name == name) return e.type;
  }
  return std::nullopt;
}

const std::vector<std::string_view>& ShotTypeNames() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> v;
    for (const auto& e : kCanonical) v.push_back(e.name);
    return v;
  }();
  return names;
}

}  // namespace cinepath::shots
