// libcinepath_ground.so: core/ground.h's Ground over the scene mesh, loaded with dlopen by
// LoadGround() (plan and export link neither Embree nor Draco).
#include <string>

#include "core/ground.h"
#include "scene/caster_ground.h"
#include "scene/glb_reader.h"
#include "scene/ray_caster.h"

namespace cinepath::scene {
namespace {

// The whole scene's mesh and its ray caster, owned here; the queries are CasterGround's.
class MeshGround : public Ground {
 public:
  explicit MeshGround(const std::string& glb_path)
      : caster_(ReadGlbFile(glb_path)), ground_(caster_, std::filesystem::path(glb_path).filename().string()) {}
  std::optional<double> SurfaceUpM(double east_m, double north_m, double from_up_m) const override {
    return ground_.SurfaceUpM(east_m, north_m, from_up_m);
  }
  const std::string& source() const override { return ground_.source(); }

 private:
  RayCaster caster_;
  CasterGround ground_;
};

}  // namespace
}  // namespace cinepath::scene

extern "C" __attribute__((visibility("default"))) cinepath::Ground* cinepath_plugin_make_ground(
    const std::string& glb_path) {
  return new cinepath::scene::MeshGround(glb_path);
}
