// libFuzzer target: ParseJsonText (simdjson's parse copied into nlohmann's tree, nlohmann itself for what
// simdjson refuses) against nlohmann's own parser. Both must accept the same texts and build the same tree,
// node types included; whatever nlohmann refuses must come back as an InputError.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "core/error.h"
#include "core/json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  cinepath::Json theirs;
  bool they_accept = true;
  try {
    theirs = cinepath::Json::parse(text);
  } catch (const cinepath::Json::exception&) {
    they_accept = false;
  }
  try {
    const cinepath::Json ours = cinepath::ParseJsonText(text, "x.json");
    if (!they_accept || ours != theirs || ours.dump() != theirs.dump()) std::abort();
  } catch (const cinepath::InputError&) {
    if (they_accept) std::abort();
  }
  return 0;
}
