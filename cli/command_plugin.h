// Subcommands whose libraries are heavy to load (photogrammetry pulls Ceres with glog, SuiteSparse and
// LAPACK, CGAL's gmp/mpfr, TBB, OpenMesh, Draco: ~45 ms of dynamic linking at every start) are built as
// shared modules beside the executable and loaded with dlopen only when that subcommand runs, so
// `cinepath --version`, `lens`, `plan` and `export` start in a few milliseconds.
//
// A plugin module defines CINEPATH_COMMAND_PLUGIN(MakeXxxCommand) once; the executable's registry
// calls LoadCommandPlugin("libcinepath_cmd_xxx.so").
#pragma once

#include <memory>
#include <string>

#include "cli/command.h"

namespace cinepath::cli {

// Loads the module (core/plugin.h search rules) and makes its command. RuntimeError when missing.
std::unique_ptr<Command> LoadCommandPlugin(const std::string& module_file_name);

}  // namespace cinepath::cli

#define CINEPATH_COMMAND_PLUGIN(factory)                                                                     \
  extern "C" __attribute__((visibility("default"))) cinepath::cli::Command* cinepath_plugin_make_command() { \
    return cinepath::cli::factory().release();                                                               \
  }
