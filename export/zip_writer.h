// A minimal, deterministic ZIP writer (PKWARE APPNOTE 6.3: local headers, central directory, end
// record) with "stored" entries — what a KMZ needs. Every entry carries the DOS epoch timestamp
// 1980-01-01 00:00, so the archive bytes depend only on the entries.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace cinepath::exporter {

uint32_t Crc32(std::string_view bytes);  // ISO-HDLC CRC-32 (zlib's crc32)

class ZipWriter {
 public:
  void Add(std::string name, std::string contents);  // order is kept
  std::string Finish() const;

 private:
  struct Entry {
    std::string name;
    std::string contents;
  };
  std::vector<Entry> entries_;
};

}  // namespace cinepath::exporter
