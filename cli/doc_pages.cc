#include "cli/doc_pages.h"

namespace cinepath::cli {

std::optional<std::string> DocExamples(std::string_view command) {
  for (const DocPage& page : DocPages()) {
    if (page.command != command) continue;
    std::string out;
    bool in_example = false;
    size_t start = 0;
    while (start < page.markdown.size()) {
      size_t end = page.markdown.find('\n', start);
      if (end == std::string::npos) end = page.markdown.size();
      const std::string_view line(page.markdown.data() + start, end - start);
      if (line.rfind("## ", 0) == 0) in_example = line.rfind("## Example", 0) == 0;
      if (in_example) {
        out.append(line);
        out += '\n';
      }
      start = end + 1;
    }
    if (out.empty()) return std::nullopt;
    return out;
  }
  return std::nullopt;
}

}  // namespace cinepath::cli
