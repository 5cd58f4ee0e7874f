#include "viewer/base64.h"

#include <gtest/gtest.h>

namespace cinepath::viewer {
namespace {

TEST(Base64, Rfc4648Vectors) {
  EXPECT_EQ(Base64Encode(""), "");
  EXPECT_EQ(Base64Encode("f"), "Zg==");
  EXPECT_EQ(Base64Encode("fo"), "Zm8=");
  EXPECT_EQ(Base64Encode("foo"), "Zm9v");
  EXPECT_EQ(Base64Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64Encode("foobar"), "Zm9vYmFy");
}

TEST(Base64, HighBytes) { EXPECT_EQ(Base64Encode(std::string("\xff\xfe\x00", 3)), "//4A"); }

}  // namespace
}  // namespace cinepath::viewer
