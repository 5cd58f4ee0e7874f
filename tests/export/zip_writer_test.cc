#include "export/zip_writer.h"

#include <cstring>

#include <gtest/gtest.h>

namespace cinepath::exporter {
namespace {

uint32_t U32(const std::string& s, size_t at) {
  uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}
uint16_t U16(const std::string& s, size_t at) {
  uint16_t v;
  std::memcpy(&v, s.data() + at, 2);
  return v;
}

TEST(ZipWriter, Crc32CheckValue) { EXPECT_EQ(Crc32("123456789"), 0xCBF43926u); }

TEST(ZipWriter, LayoutAndDeterminism) {
  ZipWriter zip;
  zip.Add("wpmz/template.kml", "<kml/>\n");
  zip.Add("wpmz/waylines.wpml", "hello");
  const std::string bytes = zip.Finish();
  EXPECT_EQ(U32(bytes, 0), 0x04034b50u);
  EXPECT_EQ(U16(bytes, 8), 0);  // stored
  EXPECT_EQ(U32(bytes, 14), Crc32("<kml/>\n"));
  EXPECT_EQ(U32(bytes, 18), 7u);
  EXPECT_EQ(bytes.substr(30, 17), "wpmz/template.kml");
  // End of central directory: 22 bytes at the end, 2 entries, offsets consistent.
  const size_t eocd = bytes.size() - 22;
  EXPECT_EQ(U32(bytes, eocd), 0x06054b50u);
  EXPECT_EQ(U16(bytes, eocd + 10), 2);
  const uint32_t cd_size = U32(bytes, eocd + 12), cd_offset = U32(bytes, eocd + 16);
  EXPECT_EQ(cd_offset + cd_size, eocd);
  EXPECT_EQ(U32(bytes, cd_offset), 0x02014b50u);
  ZipWriter again;
  again.Add("wpmz/template.kml", "<kml/>\n");
  again.Add("wpmz/waylines.wpml", "hello");
  EXPECT_EQ(again.Finish(), bytes);
}

}  // namespace
}  // namespace cinepath::exporter
