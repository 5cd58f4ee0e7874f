// libFuzzer target: EXIF (camera, focal length, GPS) read from a photo through the OpenImageIO plugin
// (photogrammetry/io/exif_oiio_plugin.cc), as `mesh --images` reads every photo. The input is written to a
// temporary .jpg, since the plugin opens files by name. OpenImageIO itself is not instrumented: a crash in
// it still stops the run, as a deadly signal.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "photogrammetry/io/exif_gps_abi.h"

extern "C" int cinepath_exif_read(const char* path, CinepathExifRecord* record, char* error, size_t error_size);

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/cinepath_fuzz_exif_" + std::to_string(getpid()) + ".jpg";
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  CinepathExifRecord record;
  char error[512];
  cinepath_exif_read(path.c_str(), &record, error, sizeof error);
  return 0;
}
