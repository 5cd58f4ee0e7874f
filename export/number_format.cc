#include "export/number_format.h"

#include <charconv>
#include <cmath>

#include "core/error.h"

namespace cinepath::exporter {

std::string FormatFixed(double value, int decimals) {
  CINEPATH_CHECK(std::isfinite(value));
  char buffer[64];
  auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  CINEPATH_CHECK(ec == std::errc());
  std::string text(buffer, ptr);
  // "-0.000" is the same number as "0.000": print it once, one way.
  if (text[0] == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

std::string FormatShortest(double value) {
  CINEPATH_CHECK(std::isfinite(value));
  if (value == 0) return "0";
  char buffer[64];
  auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  CINEPATH_CHECK(ec == std::errc());
  return std::string(buffer, ptr);
}

}  // namespace cinepath::exporter
