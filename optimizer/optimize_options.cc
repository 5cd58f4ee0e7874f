#include "optimizer/optimize_options.h"

#include "core/error.h"

namespace cinepath::optimizer {

OptimizeQuality ParseOptimizeQuality(const std::string& name) {
  if (name == "draft") return OptimizeQuality::kDraft;
  if (name == "standard") return OptimizeQuality::kStandard;
  if (name == "final") return OptimizeQuality::kFinal;
  throw InputError("--quality: expected draft, standard or final, got \"" + name + "\"");
}

const char* OptimizeQualityName(OptimizeQuality quality) {
  switch (quality) {
    case OptimizeQuality::kDraft: return "draft";
    case OptimizeQuality::kStandard: return "standard";
    case OptimizeQuality::kFinal: return "final";
  }
  return "standard";
}

OptimizeOptions OptimizeOptions::ForQuality(OptimizeQuality quality) {
  OptimizeOptions o;
  o.quality = quality;
  switch (quality) {
    case OptimizeQuality::kDraft:
      o.knot_spacing_s = 1.0;
      o.max_iterations = 30;
      o.function_tolerance = 1e-5;
      o.visibility_rounds = 1;
      break;
    case OptimizeQuality::kStandard:
      o.knot_spacing_s = 0.5;
      o.max_iterations = 100;
      o.function_tolerance = 1e-8;
      o.visibility_rounds = 4;
      break;
    case OptimizeQuality::kFinal:
      o.knot_spacing_s = 0.25;
      o.max_iterations = 300;
      o.function_tolerance = 1e-10;
      o.visibility_rounds = 6;
      break;
  }
  return o;
}

}  // namespace cinepath::optimizer
