// Locale-independent number text for files and messages: fixed decimals or the shortest round-trip
// form, always with '.', never "-0". Non-finite values print as "nan", "inf", "-inf" (files that must
// not hold them are validated before they are written).
#pragma once

#include <string>

namespace cinepath {

std::string FormatFixed(double value, int decimals);  // "%.{decimals}f"
std::string FormatShortest(double value);             // shortest text that reads back to the same double
// `digits` significant digits without trailing zeros ("%.{digits}g"): 2.8, 1e-06, 1.235e+04.
std::string FormatSignificant(double value, int digits = 6);

}  // namespace cinepath
