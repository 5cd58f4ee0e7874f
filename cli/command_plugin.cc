#include "cli/command_plugin.h"

#include "core/plugin.h"

namespace cinepath::cli {

std::unique_ptr<Command> LoadCommandPlugin(const std::string& module_file_name) {
  using MakeFn = Command* (*)();
  auto make = reinterpret_cast<MakeFn>(LoadPluginSymbol(module_file_name, "cinepath_plugin_make_command"));
  return std::unique_ptr<Command>(make());
}

}  // namespace cinepath::cli
