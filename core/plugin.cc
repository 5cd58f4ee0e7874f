#include "core/plugin.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <system_error>
#include <vector>

#include "core/error.h"

namespace cinepath {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> CandidateDirectories() {
  std::vector<fs::path> dirs;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) dirs.push_back(exe.parent_path());
  if (const char* env = std::getenv("CINEPATH_PLUGIN_DIR"); env != nullptr && *env != '\0') dirs.emplace_back(env);
  if (!ec) dirs.push_back(exe.parent_path().parent_path() / "lib" / "cinepath");
  return dirs;
}

struct Loaded {
  void* handle = nullptr;
  std::string path;
};

}  // namespace

void* LoadPluginSymbol(const std::string& file_name, const char* symbol, std::string* loaded_from) {
  static std::mutex mutex;
  static std::map<std::string, Loaded> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = loaded.find(file_name);
  if (it == loaded.end()) {
    std::string tried, errors;
    Loaded found;
    for (const fs::path& dir : CandidateDirectories()) {
      const fs::path candidate = dir / file_name;
      tried += (tried.empty() ? "" : ", ") + candidate.string();
      if (!fs::exists(candidate)) continue;
      void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle == nullptr) {
        const char* err = dlerror();
        errors += std::string("; ") + (err ? err : candidate.string() + ": dlopen failed");
        continue;
      }
      found = {handle, candidate.string()};
      break;
    }
    if (found.handle == nullptr) {
      throw RuntimeError("plugin " + file_name + " not found or not loadable (looked in: " + tried +
                         "; set CINEPATH_PLUGIN_DIR to its folder)" + errors);
    }
    it = loaded.emplace(file_name, found).first;
  }
  dlerror();
  void* address = dlsym(it->second.handle, symbol);
  if (address == nullptr) {
    const char* err = dlerror();
    throw RuntimeError(it->second.path + ": symbol " + symbol + " missing" + (err ? std::string(": ") + err : ""));
  }
  if (loaded_from) *loaded_from = it->second.path;
  return address;
}

}  // namespace cinepath
