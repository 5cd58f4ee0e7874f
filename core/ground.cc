#include "core/ground.h"

#include "core/plugin.h"

namespace cinepath {

std::unique_ptr<Ground> LoadGround(const std::filesystem::path& glb,
                                   const std::optional<Eigen::Isometry3d>& frame_from_mesh) {
  // The motion crosses the plugin's C boundary as its 4 x 4 matrix, column-major (null: none).
  using MakeGround = Ground* (*)(const std::string& glb_path, const double* frame_from_mesh);
  auto make = reinterpret_cast<MakeGround>(LoadPluginSymbol("libcinepath_ground.so", "cinepath_plugin_make_ground"));
  return std::unique_ptr<Ground>(make(glb.string(), frame_from_mesh ? frame_from_mesh->matrix().data() : nullptr));
}

}  // namespace cinepath
