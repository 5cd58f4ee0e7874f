// libcinepath_ground.so: core/ground.h's Ground over the scene mesh, loaded with dlopen by
// LoadGround() (plan and export link neither Embree nor Draco).
#include <string>

#include <Eigen/Geometry>

#include "core/ground.h"
#include "scene/caster_ground.h"
#include "scene/glb_reader.h"
#include "scene/ray_caster.h"

namespace cinepath::scene {
namespace {

// The mesh of `glb_path`, its vertices moved by the 4 x 4 matrix `frame_from_mesh` (column-major) when given.
SceneMesh ReadMeshInFrame(const std::string& glb_path, const double* frame_from_mesh) {
  SceneMesh mesh = ReadGlbFile(glb_path);
  if (frame_from_mesh) {
    Eigen::Isometry3d motion;
    motion.matrix() = Eigen::Map<const Eigen::Matrix4d>(frame_from_mesh);
    for (Eigen::Vector3d& p : mesh.positions_enu_m) p = motion * p;
  }
  return mesh;
}

// The whole scene's mesh and its ray caster, owned here; the queries are CasterGround's.
class MeshGround : public Ground {
 public:
  MeshGround(const std::string& glb_path, const double* frame_from_mesh)
      : caster_(ReadMeshInFrame(glb_path, frame_from_mesh)),
        ground_(caster_, std::filesystem::path(glb_path).filename().string()) {}
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
    const std::string& glb_path, const double* frame_from_mesh) {
  return new cinepath::scene::MeshGround(glb_path, frame_from_mesh);
}
