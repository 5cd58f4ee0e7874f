// The ground of a scene, as `plan --scene` and `export --scene` ask about it: how high is the surface
// under a point. The scene module answers with ray casts against the mesh (scene/ray_caster.h), loaded
// as a plugin (scene/ground_plugin.cc) so that Embree stays out of the start-up path of the commands
// that do not need a mesh.
#pragma once

#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Geometry>

namespace cinepath {

class Ground {
 public:
  virtual ~Ground() = default;
  // ENU up (m) of the highest surface at (east, north) at or below `from_up_m` (a ray cast straight
  // down from there); nullopt where the mesh has nothing below.
  virtual std::optional<double> SurfaceUpM(double east_m, double north_m,
                                           double from_up_m = std::numeric_limits<double>::infinity()) const = 0;
  // The mesh's file name, for messages.
  virtual const std::string& source() const = 0;
};

// Reads the GLB (scene.glb; Draco too) and builds its ray caster, through the plugin
// libcinepath_ground.so. InputError for a malformed or empty mesh, RuntimeError when the plugin is missing.
// With `frame_from_mesh` the mesh's vertices are moved by it first, so the ground answers in that frame
// (a scene's mesh in the frame of a shot list made about another origin: core/reframe.h's EnuFromEnu).
std::unique_ptr<Ground> LoadGround(const std::filesystem::path& glb,
                                   const std::optional<Eigen::Isometry3d>& frame_from_mesh = std::nullopt);

}  // namespace cinepath
