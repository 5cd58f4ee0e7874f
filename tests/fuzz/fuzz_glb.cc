// libFuzzer target: scene.glb read into ENU triangles (scene/glb_reader.h: glTF binary, Draco, textures),
// the reader every stage after `mesh` uses.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "scene/glb_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    cinepath::scene::ReadGlbBytes(std::string_view(reinterpret_cast<const char*>(data), size), "scene.glb");
  } catch (const cinepath::InputError&) {}
  return 0;
}
