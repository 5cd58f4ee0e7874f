// `--depfile FILE`: a make-style dependency line naming what a run read, so Makefiles rebuild an
// output when any input changes:  "out/plan.json: shots.json scene.json"
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cinepath {

// Escapes spaces, '#', '$' and backslashes the way make reads them.
std::string EscapeForMake(const std::string& path);

// "t1 t2: d1 d2\n" with every path escaped. Dependencies keep their order, duplicates dropped.
std::string FormatDepfile(const std::vector<std::string>& targets, const std::vector<std::string>& dependencies);

// Writes the line atomically.
void WriteDepfile(const std::filesystem::path& depfile, const std::vector<std::string>& targets,
                  const std::vector<std::string>& dependencies);

}  // namespace cinepath
