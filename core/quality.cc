#include "core/quality.h"

#include "core/error.h"

namespace cinepath {

const std::vector<std::string>& QualityNames() {
  static const std::vector<std::string> names = {"draft", "standard", "final"};
  return names;
}

Quality ParseQuality(const std::string& text, const std::string& where) {
  if (text == "draft") return Quality::kDraft;
  if (text == "standard") return Quality::kStandard;
  if (text == "final") return Quality::kFinal;
  throw InputError(Located(where, "must be draft, standard or final, not '" + text + "'"));
}

const char* QualityName(Quality quality) {
  switch (quality) {
    case Quality::kDraft: return "draft";
    case Quality::kStandard: return "standard";
    case Quality::kFinal: return "final";
  }
  return "?";
}

}  // namespace cinepath
