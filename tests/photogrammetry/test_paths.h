// Test support: where test data lives.
#pragma once

#include <cstdlib>
#include <filesystem>

namespace cinepath::photogrammetry::testing {

inline std::filesystem::path TestDataDir() { return CINEPATH_TEST_DATA_DIR; }

// A fresh, empty scratch folder under the system temp dir.
inline std::filesystem::path ScratchDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("cinepath_georef_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace cinepath::photogrammetry::testing
