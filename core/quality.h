// The speed-for-accuracy ladder every expensive stage offers: `mesh`, `optimize` and `render` take
// `--quality draft|standard|final`, and each maps a rung to its own preset (docs/design.md
// "Conventions", Presets; the time and error of each preset are in bench/RESULTS.md).
//   const Quality q = ParseQuality("final");      // InputError naming `where` for anything else
//   report["quality"] = QualityName(q);
#pragma once

#include <string>
#include <vector>

namespace cinepath {

enum class Quality { kDraft, kStandard, kFinal };

// Parses "draft" | "standard" | "final"; throws InputError naming `where` otherwise.
Quality ParseQuality(const std::string& text, const std::string& where = "--quality");
const char* QualityName(Quality quality);
// {"draft", "standard", "final"}, cheapest first: the CLI's choices and help come from here.
const std::vector<std::string>& QualityNames();

}  // namespace cinepath
