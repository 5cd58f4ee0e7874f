#include "export/number_format.h"

#include <gtest/gtest.h>

namespace cinepath::exporter {
namespace {

TEST(NumberFormat, FixedAndShortest) {
  EXPECT_EQ(FormatFixed(47.3977419, 8), "47.39774190");
  EXPECT_EQ(FormatFixed(-0.0000000001, 6), "0.000000");  // no "-0"
  EXPECT_EQ(FormatFixed(-1.5, 2), "-1.50");
  EXPECT_EQ(FormatShortest(0.1), "0.1");
  EXPECT_EQ(FormatShortest(-0.0), "0");
  EXPECT_EQ(std::stod(FormatShortest(1.0 / 3.0)), 1.0 / 3.0);
}

}  // namespace
}  // namespace cinepath::exporter
