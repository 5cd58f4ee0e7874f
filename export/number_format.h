// Locale-independent number text for mission files: fixed decimals or the shortest round-trip form.
#pragma once

#include <string>

namespace cinepath::exporter {

std::string FormatFixed(double value, int decimals);  // "%.{decimals}f" with '.', no "-0"
std::string FormatShortest(double value);             // shortest text that reads back to the same double

}  // namespace cinepath::exporter
