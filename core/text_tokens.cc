#include "core/text_tokens.h"

namespace cinepath {

bool IsTokenSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::vector<std::string_view> WhitespaceTokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsTokenSpace(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !IsTokenSpace(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

}  // namespace cinepath
