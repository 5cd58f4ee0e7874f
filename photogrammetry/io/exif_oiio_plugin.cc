// EXIF reader plugin on OpenImageIO: a shared MODULE library, loaded with dlopen only when EXIF is
// needed (exif_gps.cc), so that the ~250 ms OpenImageIO costs at start-up is paid only then.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "photogrammetry/io/exif_gps_abi.h"

namespace {

void CopyString(const std::string& s, char* out, size_t size) { std::snprintf(out, size, "%s", s.c_str()); }

bool ReadDegrees(const OIIO::ImageSpec& spec, const char* name, double* degrees) {
  float dms[3] = {0, 0, 0};
  if (!spec.getattribute(name, OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 3), dms)) return false;
  *degrees = double(dms[0]) + double(dms[1]) / 60.0 + double(dms[2]) / 3600.0;
  return std::isfinite(*degrees);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int cinepath_exif_read(const char* path, CinepathExifRecord* record,
                                                                         char* error, size_t error_size) {
  std::memset(record, 0, sizeof(*record));
  record->abi_version = kCinepathExifAbiVersion;
  auto input = OIIO::ImageInput::open(path);
  if (!input) {
    CopyString(OIIO::geterror(), error, error_size);
    return 0;
  }
  const OIIO::ImageSpec& spec = input->spec();
  record->width_px = spec.width;
  record->height_px = spec.height;
  CopyString(spec.get_string_attribute("Make"), record->make, sizeof(record->make));
  CopyString(spec.get_string_attribute("Model"), record->model, sizeof(record->model));

  double lat, lon;
  const OIIO::ParamValue* alt = spec.find_attribute("GPS:Altitude");
  if (ReadDegrees(spec, "GPS:Latitude", &lat) && ReadDegrees(spec, "GPS:Longitude", &lon) && alt != nullptr) {
    if (spec.get_string_attribute("GPS:LatitudeRef") == "S") lat = -lat;
    if (spec.get_string_attribute("GPS:LongitudeRef") == "W") lon = -lon;
    double alt_m = spec.get_float_attribute("GPS:Altitude", NAN);
    if (spec.get_int_attribute("GPS:AltitudeRef", 0) == 1) alt_m = -alt_m;
    if (std::isfinite(alt_m)) {
      record->has_gps = 1;
      record->lat_deg = lat;
      record->lon_deg = lon;
      record->alt_m = alt_m;
    }
  }
  const float focal = spec.get_float_attribute("Exif:FocalLength", 0.0f);
  if (std::isfinite(focal) && focal > 0) {
    record->has_focal_length = 1;
    record->focal_length_mm = focal;
  }
  const int f35 = spec.get_int_attribute("Exif:FocalLengthIn35mmFilm", 0);
  record->focal_length_35mm_mm = f35 > 0 ? f35 : 0;
  input->close();
  return 1;
}

extern "C" __attribute__((visibility("default"))) int cinepath_image_read_rgb8(const char* path, void* context,
                                                                               CinepathImageAllocFn alloc, int* width,
                                                                               int* height, char* error,
                                                                               size_t error_size) {
  auto input = OIIO::ImageInput::open(path);
  if (!input) {
    CopyString(OIIO::geterror(), error, error_size);
    return 0;
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    CopyString("empty image", error, error_size);
    return 0;
  }
  const int channels = spec.nchannels >= 3 ? 3 : 1;
  const size_t n = size_t(spec.width) * size_t(spec.height);
  unsigned char* out = alloc(context, n * 3);
  if (out == nullptr) {
    CopyString("out of memory", error, error_size);
    return 0;
  }
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, out)) {
    CopyString(input->geterror(), error, error_size);
    return 0;
  }
  if (channels == 1) {  // grey in the first n bytes: spread to RGB from the end backwards
    for (size_t i = n; i-- > 0;) out[3 * i] = out[3 * i + 1] = out[3 * i + 2] = out[i];
  }
  *width = spec.width;
  *height = spec.height;
  input->close();
  return 1;
}
