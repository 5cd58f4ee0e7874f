// libFuzzer target: scene.json (what plan --scene, optimize, render, export --scene and view read).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "core/json.h"
#include "core/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const cinepath::Json doc =
        cinepath::ParseJsonText(std::string_view(reinterpret_cast<const char*>(data), size), "scene.json");
    cinepath::ParseSceneFile(doc, "scene.json", "/nonexistent");
  } catch (const cinepath::InputError&) {}
  return 0;
}
