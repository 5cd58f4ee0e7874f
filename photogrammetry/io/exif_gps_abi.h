// The C interface between cinepath and its OpenImageIO plugin (libcinepath_exif_oiio.so, built from
// exif_oiio_plugin.cc and loaded with dlopen, see core/plugin.h): the EXIF of a photo, and a photo's
// pixels for texturing (photo_image.h). Plain C types only, so the plugin and the executable share no
// C++ ABI. Bump kCinepathExifAbiVersion on any change.
#pragma once

#include <cstddef>

extern "C" {

inline constexpr int kCinepathExifAbiVersion = 2;

struct CinepathExifRecord {
  int abi_version;
  int has_gps;     // latitude, longitude and altitude all present
  double lat_deg;  // signed with GPSLatitudeRef
  double lon_deg;  // signed with GPSLongitudeRef
  double alt_m;    // GPSAltitude, negated when GPSAltitudeRef = 1 (below sea level)
  int has_focal_length;
  double focal_length_mm;       // Exif FocalLength
  double focal_length_35mm_mm;  // Exif FocalLengthIn35mmFilm, 0 when absent
  int width_px;                 // the image as stored (not Exif PixelXDimension)
  int height_px;
  char make[64];
  char model[64];
};

// Returns 1 on success; 0 on failure with a NUL-terminated message in `error`.
typedef int (*CinepathExifReadFn)(const char* path, CinepathExifRecord* record, char* error, size_t error_size);

// Where the pixels go: returns a buffer of `bytes` bytes owned by the caller (context is passed through).
typedef unsigned char* (*CinepathImageAllocFn)(void* context, size_t bytes);
// Decodes the first subimage of `path` as 8-bit RGB, rows top to bottom (grey is replicated, alpha and
// further channels dropped) into alloc(context, width * height * 3); sets *width and *height. Returns
// 1 on success; 0 on failure with a NUL-terminated message in `error`.
typedef int (*CinepathImageReadRgb8Fn)(const char* path, void* context, CinepathImageAllocFn alloc, int* width,
                                       int* height, char* error, size_t error_size);
}

inline constexpr const char* kCinepathExifPluginFile = "libcinepath_exif_oiio.so";
inline constexpr const char* kCinepathExifReadSymbol = "cinepath_exif_read";
inline constexpr const char* kCinepathImageReadRgb8Symbol = "cinepath_image_read_rgb8";
