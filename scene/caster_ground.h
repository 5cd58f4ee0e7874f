// core/ground.h's Ground answered by a RayCaster the caller owns: the highest surface below a point is a
// ray cast straight down (RayCaster::SurfaceBelow). The ground plugin (scene/ground_plugin.cc) wraps the
// whole scene in one; `optimize` wraps the corridor it indexed, for the feasibility check's terrain test.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "core/ground.h"
#include "scene/ray_caster.h"

namespace cinepath::scene {

class CasterGround : public Ground {
 public:
  CasterGround(const RayCaster& caster, std::string source) : caster_(caster), source_(std::move(source)) {}
  std::optional<double> SurfaceUpM(double east_m, double north_m, double from_up_m) const override {
    const auto hit = caster_.SurfaceBelow(east_m, north_m, from_up_m);
    if (!hit) return std::nullopt;
    return hit->position_enu_m.z();
  }
  const std::string& source() const override { return source_; }

 private:
  const RayCaster& caster_;
  std::string source_;
};

}  // namespace cinepath::scene
