#include "cli/parse_values.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace cinepath::cli {
namespace {

bool ParseDouble(const std::string& text, double* out) {
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(begin, end, *out);
  return ec == std::errc() && ptr == end && !text.empty();
}

}  // namespace

double ParseFiniteDouble(const std::string& text, const std::string& option) {
  double v;
  if (!ParseDouble(text, &v) || !std::isfinite(v)) {
    throw InputError(option + ": expected a number, got '" + text + "'");
  }
  return v;
}

double ParseMetresOrInfinity(const std::string& text, const std::string& option) {
  if (text == "inf" || text == "infinity" || text == "Inf" || text == "INF") {
    return std::numeric_limits<double>::infinity();
  }
  double v;
  if (!ParseDouble(text, &v) || !std::isfinite(v)) {
    throw InputError(option + ": expected metres or 'inf', got '" + text + "'");
  }
  if (!(v > 0)) throw InputError(option + ": must be > 0 m, got " + text);
  return v;
}

std::pair<double, double> ParseSizeMm(const std::string& text, const std::string& option) {
  const auto x = text.find_first_of("xX");
  if (x == std::string::npos) throw InputError(option + ": expected WxH in mm, got '" + text + "'");
  const double w = ParseFiniteDouble(text.substr(0, x), option);
  const double h = ParseFiniteDouble(text.substr(x + 1), option);
  if (!(w > 0) || !(h > 0)) throw InputError(option + ": both sizes must be > 0 mm");
  return {w, h};
}

std::vector<double> ParseNumberList(const std::string& text, size_t count, const std::string& option) {
  std::vector<double> values;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    values.push_back(ParseFiniteDouble(text.substr(start, comma - start), option));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != count) {
    throw InputError(option + ": expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
  }
  return values;
}

}  // namespace cinepath::cli
