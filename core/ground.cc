#include "core/ground.h"

#include "core/plugin.h"

namespace cinepath {

std::unique_ptr<Ground> LoadGround(const std::filesystem::path& glb) {
  using MakeGround = Ground* (*)(const std::string& glb_path);
  auto make = reinterpret_cast<MakeGround>(LoadPluginSymbol("libcinepath_ground.so", "cinepath_plugin_make_ground"));
  return std::unique_ptr<Ground>(make(glb.string()));
}

}  // namespace cinepath
