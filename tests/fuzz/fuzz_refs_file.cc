// libFuzzer target: references file (image_name lat lon alt). Parse or throw cinepath::InputError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "photogrammetry/io/refs_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    cinepath::photogrammetry::ParseReferences(std::string_view(reinterpret_cast<const char*>(data), size), "refs.txt");
  } catch (const cinepath::InputError&) {}
  return 0;
}
