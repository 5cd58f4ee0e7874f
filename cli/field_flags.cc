#include "cli/field_flags.h"

#include <cctype>

namespace cinepath::cli {
namespace {

bool IsWordChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

}  // namespace

std::string WithFlagNames(const std::string& message_in, const FieldFlags& flags) {
  std::string message = message_in;
  for (const auto& [field, flag] : flags) {
    const std::string quoted = "`" + std::string(field) + "`";
    for (size_t pos = 0; (pos = message.find(quoted, pos)) != std::string::npos; pos += flag.size()) {
      message.replace(pos, quoted.size(), flag);
    }
  }
  const size_t colon = message.find(": ");
  if (colon == std::string::npos) return message;
  std::string out = message.substr(0, colon);
  for (const auto& [field, flag] : flags) {
    size_t pos = 0;
    while ((pos = out.find(field, pos)) != std::string::npos) {
      const size_t end = pos + field.size();
      const bool whole = (pos == 0 || !IsWordChar(out[pos - 1])) && (end == out.size() || !IsWordChar(out[end]));
      // A flag already in the text ("--target-faces") is left alone.
      const bool after_dashes = pos >= 2 && out.compare(pos - 2, 2, "--") == 0;
      if (whole && !after_dashes) {
        out.replace(pos, field.size(), flag);
        pos += flag.size();
      } else {
        pos = end;
      }
    }
  }
  return out + message.substr(colon);
}

}  // namespace cinepath::cli
