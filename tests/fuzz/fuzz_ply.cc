// libFuzzer target: PLY reader (ASCII and binary). Any input must parse or throw cinepath::InputError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "photogrammetry/io/ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    cinepath::photogrammetry::ParsePly(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ply");
  } catch (const cinepath::InputError&) {}
  return 0;
}
