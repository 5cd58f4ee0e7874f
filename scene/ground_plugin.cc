// libcinepath_ground.so: core/ground.h's Ground over the scene mesh, loaded with dlopen by
// LoadGround() (plan and export link neither Embree nor Draco).
#include <string>

#include "core/ground.h"
#include "scene/glb_reader.h"
#include "scene/ray_caster.h"

namespace cinepath::scene {
namespace {

class MeshGround : public Ground {
 public:
  explicit MeshGround(const std::string& glb_path)
      : source_(std::filesystem::path(glb_path).filename().string()), caster_(ReadGlbFile(glb_path)) {}

  std::optional<double> SurfaceUpM(double east_m, double north_m, double from_up_m) const override {
    const auto hit = caster_.SurfaceBelow(east_m, north_m, from_up_m);
    if (!hit) return std::nullopt;
    return hit->position_enu_m.z();
  }
  const std::string& source() const override { return source_; }

 private:
  std::string source_;
  RayCaster caster_;
};

}  // namespace
}  // namespace cinepath::scene

extern "C" __attribute__((visibility("default"))) cinepath::Ground* cinepath_plugin_make_ground(
    const std::string& glb_path) {
  return new cinepath::scene::MeshGround(glb_path);
}
