// Library code reports the option *field* that is wrong ("target_faces: must be > 0"), never a flag:
// only cli/ knows how its flags are spelled. A command lists which flag binds which field, and the
// CLI shows the flag in the message ("--target-faces: must be > 0").
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cinepath::cli {

using FieldFlags = std::vector<std::pair<std::string_view, std::string_view>>;  // {field, flag}

// Replaces the field names of `flags` that stand as whole words (delimited by characters other than
// letters, digits and '_') in the message's location, the text before its first ": ", by their flags:
// "target_faces and max_error_m: give at most one" -> "--target-faces and --max-error-m: ...", and
// fields quoted in backticks anywhere ("pass `scene_origin`" -> "pass --scene").
std::string WithFlagNames(const std::string& message, const FieldFlags& flags);

}  // namespace cinepath::cli
