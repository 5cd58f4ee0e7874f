// libFuzzer target: ground control point list (OpenDroneMap gcp_list.txt: a coordinate-system header
// line, then "geo_x geo_y geo_z px py image [name]" lines). Parse or throw cinepath::InputError.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "photogrammetry/io/gcp_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    cinepath::photogrammetry::ParseGcpFile(std::string_view(reinterpret_cast<const char*>(data), size), "gcp_list.txt");
  } catch (const cinepath::InputError&) {}
  return 0;
}
