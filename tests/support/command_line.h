// Test helpers for the tests that run the real binaries (the `cinepath` executable, `colmap`): a shell
// word for a path, a file's whole text, and a temporary folder of the test's own.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace cinepath::testing {

// `s` as one single-quoted shell word.
inline std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

inline std::string ReadText(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// A new folder under the temporary directory, stem_XXXXXX (empty path when it cannot be made): several
// checkouts of the project may run one test at the same time, and a fixed name would be shared.
inline std::filesystem::path MakeTempDir(const std::string& stem) {
  std::string pattern = (std::filesystem::temp_directory_path() / (stem + "_XXXXXX")).string();
  if (!mkdtemp(pattern.data())) return {};
  return pattern;
}

}  // namespace cinepath::testing
