// Parsing of option values shared by subcommands ("inf", "36x24", "47.1,8.5,400").
// Errors name the option: InputError("--focus-m: expected metres or 'inf', got 'abc'").
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace cinepath::cli {

// A finite double, or +infinity for "inf"/"infinity". Rejects trailing garbage.
double ParseMetresOrInfinity(const std::string& text, const std::string& option);
// A finite double; rejects trailing garbage, NaN and infinity.
double ParseFiniteDouble(const std::string& text, const std::string& option);
// "WxH" in mm, both > 0.
std::pair<double, double> ParseSizeMm(const std::string& text, const std::string& option);
// Comma-separated finite numbers, exactly `count` of them.
std::vector<double> ParseNumberList(const std::string& text, size_t count, const std::string& option);

}  // namespace cinepath::cli
