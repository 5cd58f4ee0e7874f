#include "export/zip_writer.h"

#include <array>

#include "core/error.h"

namespace cinepath::exporter {

namespace {

std::array<uint32_t, 256> MakeCrcTable() {
  std::array<uint32_t, 256> table{};
  for (uint32_t i = 0; i < 256; ++i) {
    uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}

void PutU16(std::string& out, uint32_t v) {
  out.push_back(static_cast<char>(v & 0xFF));
  out.push_back(static_cast<char>((v >> 8) & 0xFF));
}
void PutU32(std::string& out, uint32_t v) {
  PutU16(out, v & 0xFFFF);
  PutU16(out, v >> 16);
}

constexpr uint32_t kDosTime = 0;                        // 00:00:00
constexpr uint32_t kDosDate = (0 << 9) | (1 << 5) | 1;  // 1980-01-01
constexpr uint32_t kVersion = 20;                       // 2.0: stored entries, folders

}  // namespace

uint32_t Crc32(std::string_view bytes) {
  static const std::array<uint32_t, 256> table = MakeCrcTable();
  uint32_t c = 0xFFFFFFFFu;
  for (char b : bytes) c = table[(c ^ static_cast<uint8_t>(b)) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

void ZipWriter::Add(std::string name, std::string contents) {
  CINEPATH_CHECK(name.size() < 0xFFFF && contents.size() < 0xFFFFFFFFu);
  entries_.push_back({std::move(name), std::move(contents)});
}

std::string ZipWriter::Finish() const {
  std::string out;
  std::string central;
  for (const Entry& e : entries_) {
    const uint32_t crc = Crc32(e.contents);
    const uint32_t size = static_cast<uint32_t>(e.contents.size());
    const uint32_t offset = static_cast<uint32_t>(out.size());
    PutU32(out, 0x04034b50);
    PutU16(out, kVersion);
    PutU16(out, 0);  // flags
    PutU16(out, 0);  // method: stored
    PutU16(out, kDosTime);
    PutU16(out, kDosDate);
    PutU32(out, crc);
    PutU32(out, size);
    PutU32(out, size);
    PutU16(out, static_cast<uint32_t>(e.name.size()));
    PutU16(out, 0);  // extra length
    out += e.name;
    out += e.contents;

    PutU32(central, 0x02014b50);
    PutU16(central, kVersion);  // made by (MS-DOS attributes)
    PutU16(central, kVersion);  // needed
    PutU16(central, 0);
    PutU16(central, 0);
    PutU16(central, kDosTime);
    PutU16(central, kDosDate);
    PutU32(central, crc);
    PutU32(central, size);
    PutU32(central, size);
    PutU16(central, static_cast<uint32_t>(e.name.size()));
    PutU16(central, 0);  // extra
    PutU16(central, 0);  // comment
    PutU16(central, 0);  // disk
    PutU16(central, 0);  // internal attributes
    PutU32(central, 0);  // external attributes
    PutU32(central, offset);
    central += e.name;
  }
  const uint32_t central_offset = static_cast<uint32_t>(out.size());
  out += central;
  PutU32(out, 0x06054b50);
  PutU16(out, 0);
  PutU16(out, 0);
  PutU16(out, static_cast<uint32_t>(entries_.size()));
  PutU16(out, static_cast<uint32_t>(entries_.size()));
  PutU32(out, static_cast<uint32_t>(central.size()));
  PutU32(out, central_offset);
  PutU16(out, 0);  // comment length
  return out;
}

}  // namespace cinepath::exporter
