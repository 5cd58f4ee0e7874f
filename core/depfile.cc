#include "core/depfile.h"

#include <algorithm>

#include "core/file_io.h"

namespace cinepath {

std::string EscapeForMake(const std::string& path) {
  std::string out;
  out.reserve(path.size());
  for (char c : path) {
    switch (c) {
      case ' ':
      case '#':
      case '\\':
        out.push_back('\\');
        out.push_back(c);
        break;
      case '$': out += "$$"; break;
      default: out.push_back(c);
    }
  }
  return out;
}

std::string FormatDepfile(const std::vector<std::string>& targets, const std::vector<std::string>& dependencies) {
  std::string line;
  for (size_t i = 0; i < targets.size(); ++i) {
    if (i) line.push_back(' ');
    line += EscapeForMake(targets[i]);
  }
  line.push_back(':');
  std::vector<std::string> seen;
  for (const auto& d : dependencies) {
    if (std::find(seen.begin(), seen.end(), d) != seen.end()) continue;
    seen.push_back(d);
    line.push_back(' ');
    line += EscapeForMake(d);
  }
  line.push_back('\n');
  return line;
}

void WriteDepfile(const std::filesystem::path& depfile, const std::vector<std::string>& targets,
                  const std::vector<std::string>& dependencies) {
  WriteFileAtomic(depfile, FormatDepfile(targets, dependencies));
}

}  // namespace cinepath
