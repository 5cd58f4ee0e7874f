#include "photogrammetry/io/refs_file.h"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/file_io.h"
#include "core/text_tokens.h"

namespace cinepath::photogrammetry {
std::vector<ImageReference> ParseReferences(std::string_view text, const std::string& source) {
  std::vector<ImageReference> refs;
  std::map<std::string, std::string> seen;
  ForEachDataLine(text, [&](std::string_view, size_t line_number, const std::vector<std::string_view>& tokens) {
    const std::string where = source + ": line " + std::to_string(line_number);
    if (tokens.size() != 4) {
      throw InputError(
          Located(where, "expected 'image_name lat lon alt', found " + std::to_string(tokens.size()) + " fields"));
    }
    double values[3];
    const char* names[3] = {"latitude", "longitude", "altitude"};
    for (int k = 0; k < 3; ++k) {
      const std::string_view t = tokens[k + 1];
      const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), values[k]);
      if (ec != std::errc() || ptr != t.data() + t.size() || !std::isfinite(values[k])) {
        throw InputError(Located(where, std::string(names[k]) + ": '" + std::string(t) + "' is not a finite number"));
      }
    }
    if (std::abs(values[0]) > 90) throw InputError(Located(where, "latitude outside [-90, 90]"));
    if (values[1] < -180 || values[1] > 360) throw InputError(Located(where, "longitude outside [-180, 360]"));
    ImageReference ref{std::string(tokens[0]), values[0], values[1], values[2], where};
    const auto [it, inserted] = seen.emplace(ref.image_name, where);
    if (!inserted) {
      throw InputError(Located(where, "image '" + ref.image_name + "' already has a reference (" + it->second + ")"));
    }
    refs.push_back(std::move(ref));
  });
  return refs;
}

std::vector<ImageReference> ReadReferencesFile(const std::filesystem::path& path) {
  return ParseReferences(ReadFileToString(path), path.string());
}

}  // namespace cinepath::photogrammetry
