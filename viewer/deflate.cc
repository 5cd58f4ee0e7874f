#include "viewer/deflate.h"

#include <zlib.h>

#include "core/error.h"

namespace cinepath::viewer {

std::string DeflateZlib(std::string_view bytes) {
  uLongf size = compressBound(uLong(bytes.size()));
  std::string out(size, '\0');
  const int status = compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                               reinterpret_cast<const Bytef*>(bytes.data()), uLong(bytes.size()), 9);
  if (status != Z_OK) throw RuntimeError("deflate: zlib error " + std::to_string(status));
  out.resize(size);
  return out;
}

std::string InflateZlib(std::string_view compressed) {
  z_stream stream{};
  if (inflateInit(&stream) != Z_OK) throw RuntimeError("inflate: zlib cannot start");
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = uInt(compressed.size());
  std::string out;
  char buffer[65536];
  int status = Z_OK;
  while (status == Z_OK) {
    stream.next_out = reinterpret_cast<Bytef*>(buffer);
    stream.avail_out = sizeof buffer;
    status = inflate(&stream, Z_NO_FLUSH);
    out.append(buffer, sizeof buffer - stream.avail_out);
  }
  inflateEnd(&stream);
  if (status != Z_STREAM_END) throw RuntimeError("inflate: corrupt zlib stream");
  return out;
}

}  // namespace cinepath::viewer
