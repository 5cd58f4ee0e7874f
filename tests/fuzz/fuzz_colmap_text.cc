// libFuzzer target: COLMAP text readers (cameras.txt, images.txt, points3D.txt). The first byte picks
// the file kind. Any input must either parse or throw cinepath::InputError; nothing else.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "photogrammetry/io/colmap_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string_view body(reinterpret_cast<const char*>(data) + 1, size - 1);
  cinepath::photogrammetry::ColmapModel model;
  cinepath::photogrammetry::ColmapLocations where;
  try {
    switch (data[0] % 3) {
      case 0: cinepath::photogrammetry::ParseColmapCamerasText(body, "cameras.txt", model); break;
      case 1: cinepath::photogrammetry::ParseColmapImagesText(body, "images.txt", model, &where); break;
      default: cinepath::photogrammetry::ParseColmapPoints3DText(body, "points3D.txt", model, &where); break;
    }
    cinepath::photogrammetry::ValidateColmapModel(model, where);
  } catch (const cinepath::InputError&) {}
  return 0;
}
