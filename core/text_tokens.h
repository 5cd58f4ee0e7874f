// Reading line-based text input formats (COLMAP text models, reference and GCP lists, PLY headers):
// lines, and whitespace-separated tokens as views into the line.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

namespace cinepath {

// Space, tab, CR, VT, FF: the separators every text format we read accepts ('\n' ends the line).
bool IsTokenSpace(char c);

// The non-empty runs of non-space characters in `line`, in order.
std::vector<std::string_view> WhitespaceTokens(std::string_view line);

// Calls fn(line, line_number, tokens) for every line of `text` that carries data: lines split at
// '\n' and numbered from 1; blank lines and lines whose first token starts with '#' are skipped.
template <typename Fn>
void ForEachDataLine(std::string_view text, Fn&& fn) {
  size_t pos = 0, line_number = 0;
  while (true) {
    size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    ++line_number;
    const std::vector<std::string_view> tokens = WhitespaceTokens(line);
    if (!tokens.empty() && tokens[0].front() != '#') fn(line, line_number, tokens);
    if (end == text.size()) return;
    pos = end + 1;
  }
}

}  // namespace cinepath
