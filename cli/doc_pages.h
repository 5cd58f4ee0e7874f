// The docs/<command>.md pages, compiled into the executable (cmake/EmbedDocs.cmake), for
// `cinepath help <command>`.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cinepath::cli {

struct DocPage {
  std::string command;
  std::string markdown;
};

const std::vector<DocPage>& DocPages();

// The page's example sections ("## Example", "## Examples", "## Example ..."), with their headings;
// nullopt when the command has no page or the page has none.
std::optional<std::string> DocExamples(std::string_view command);

}  // namespace cinepath::cli
