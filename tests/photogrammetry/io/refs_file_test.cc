#include "photogrammetry/io/refs_file.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

TEST(RefsFile, Parses) {
  const auto refs = ParseReferences(
      "# image lat lon alt\n\nDJI_0018.JPG 46.8426070833 -91.9945598889 198.309\r\n"
      "  DJI_0019.JPG\t46.8426906667\t-91.9944272778\t198.609\n",
      "refs.txt");
  ASSERT_EQ(refs.size(), 2u);
  EXPECT_EQ(refs[0].image_name, "DJI_0018.JPG");
  EXPECT_DOUBLE_EQ(refs[0].lat_deg, 46.8426070833);
  EXPECT_DOUBLE_EQ(refs[0].lon_deg, -91.9945598889);
  EXPECT_DOUBLE_EQ(refs[1].alt_m, 198.609);
  EXPECT_EQ(refs[1].where, "refs.txt: line 4");
}

std::string ErrorOf(const std::string& text) {
  try {
    ParseReferences(text, "refs.txt");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RefsFile, ErrorsNameTheLine) {
  EXPECT_EQ(ErrorOf("a.jpg 1 2\n"), "refs.txt: line 1: expected 'image_name lat lon alt', found 3 fields");
  EXPECT_EQ(ErrorOf("#\na.jpg 1 2 3 4\n"), "refs.txt: line 2: expected 'image_name lat lon alt', found 5 fields");
  EXPECT_EQ(ErrorOf("a.jpg 91 2 3\n"), "refs.txt: line 1: latitude outside [-90, 90]");
  EXPECT_EQ(ErrorOf("a.jpg 1 nan 3\n"), "refs.txt: line 1: longitude: 'nan' is not a finite number");
  EXPECT_EQ(ErrorOf("a.jpg 1 2 x\n"), "refs.txt: line 1: altitude: 'x' is not a finite number");
  EXPECT_EQ(ErrorOf("a.jpg 1 2 3\na.jpg 1 2 3"),
            "refs.txt: line 2: image 'a.jpg' already has a reference (refs.txt: line 1)");
}

}  // namespace
}  // namespace cinepath::photogrammetry
