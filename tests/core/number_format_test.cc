#include "core/number_format.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace cinepath {
namespace {

TEST(NumberFormat, FixedAndShortest) {
  EXPECT_EQ(FormatFixed(47.3977419, 8), "47.39774190");
  EXPECT_EQ(FormatFixed(-0.0000000001, 6), "0.000000");  // no "-0"
  EXPECT_EQ(FormatFixed(-1.5, 2), "-1.50");
  EXPECT_EQ(FormatFixed(2.5, 0), "2");  // round half to even, as printf
  EXPECT_EQ(FormatShortest(0.1), "0.1");
  EXPECT_EQ(FormatShortest(-0.0), "0");
  EXPECT_EQ(std::stod(FormatShortest(1.0 / 3.0)), 1.0 / 3.0);
}

TEST(NumberFormat, ExtremesAndNonFinite) {
  EXPECT_EQ(FormatFixed(std::numeric_limits<double>::max(), 2).size(), 309u + 3u);
  EXPECT_EQ(FormatFixed(std::nan(""), 3), "nan");
  EXPECT_EQ(FormatFixed(-HUGE_VAL, 3), "-inf");
  EXPECT_EQ(FormatShortest(HUGE_VAL), "inf");
}

TEST(NumberFormat, SignificantDigitsAsPrintfG) {
  EXPECT_EQ(FormatSignificant(2.8), "2.8");
  EXPECT_EQ(FormatSignificant(1e-6), "1e-06");
  EXPECT_EQ(FormatSignificant(12345.678, 4), "1.235e+04");
  EXPECT_EQ(FormatSignificant(1440.0, 4), "1440");
  EXPECT_EQ(FormatSignificant(-0.0), "0");
  EXPECT_EQ(FormatSignificant(std::nan("")), "nan");
}

}  // namespace
}  // namespace cinepath
