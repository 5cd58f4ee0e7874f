// Splitting a line of a text input format (COLMAP text models, reference and GCP lists, PLY
// headers) into whitespace-separated tokens, as views into the line.
#pragma once

#include <string_view>
#include <vector>

namespace cinepath {

// Space, tab, CR, VT, FF: the separators every text format we read accepts ('\n' ends the line).
bool IsTokenSpace(char c);

// The non-empty runs of non-space characters in `line`, in order.
std::vector<std::string_view> WhitespaceTokens(std::string_view line);

}  // namespace cinepath
