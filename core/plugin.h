// Optional shared MODULE libraries loaded with dlopen only when a feature needs them, so that heavy
// dependencies (OpenImageIO costs ~250 ms at process start) do not slow every subcommand's start-up.
//
// A plugin file is looked for, in order: next to the running executable (/proc/self/exe), in
// $CINEPATH_PLUGIN_DIR, then in <executable dir>/../lib/cinepath (the install layout). The library
// stays loaded for the life of the process.
#pragma once

#include <string>

namespace cinepath {

// The address of `symbol` in plugin `file_name` (e.g. "libcinepath_exif_oiio.so"). RuntimeError naming
// every place looked in, or dlerror(), when the file or the symbol is missing. `loaded_from` (optional)
// receives the path that was loaded. Thread-safe.
void* LoadPluginSymbol(const std::string& file_name, const char* symbol, std::string* loaded_from = nullptr);

}  // namespace cinepath
