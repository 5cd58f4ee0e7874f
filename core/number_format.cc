#include "core/number_format.h"

#include <charconv>
#include <cmath>

#include "core/error.h"

namespace cinepath {
namespace {

const char* NonFiniteText(double value) { return std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf"; }

}  // namespace

std::string FormatFixed(double value, int decimals) {
  if (!std::isfinite(value)) return NonFiniteText(value);
  char buffer[400];  // DBL_MAX has 309 integer digits
  auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  CINEPATH_CHECK(ec == std::errc());
  std::string text(buffer, ptr);
  // "-0.000" is the same number as "0.000": print it once, one way.
  if (text[0] == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

std::string FormatShortest(double value) {
  if (!std::isfinite(value)) return NonFiniteText(value);
  if (value == 0) return "0";
  char buffer[64];
  auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  CINEPATH_CHECK(ec == std::errc());
  return std::string(buffer, ptr);
}

std::string FormatSignificant(double value, int digits) {
  if (!std::isfinite(value)) return NonFiniteText(value);
  if (value == 0) return "0";
  char buffer[64];
  auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, digits);
  CINEPATH_CHECK(ec == std::errc());
  return std::string(buffer, ptr);
}

}  // namespace cinepath
