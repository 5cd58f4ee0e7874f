#include "viewer/deflate.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::viewer {
namespace {

TEST(Deflate, RoundTripsAndShrinksRepetitiveBytes) {
  std::string bytes;
  for (int i = 0; i < 100000; ++i) bytes.push_back(char(i % 7));
  const std::string packed = DeflateZlib(bytes);
  EXPECT_LT(packed.size(), bytes.size() / 20);
  EXPECT_EQ(uint8_t(packed[0]), 0x78);  // a zlib header, what DecompressionStream("deflate") reads
  EXPECT_EQ(InflateZlib(packed), bytes);
}

TEST(Deflate, SameBytesEachRun) { EXPECT_EQ(DeflateZlib("previs previs previs"), DeflateZlib("previs previs previs")); }

TEST(Deflate, CorruptInputIsAnError) { EXPECT_THROW(InflateZlib("not zlib"), RuntimeError); }

}  // namespace
}  // namespace cinepath::viewer
