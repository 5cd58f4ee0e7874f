#include "preview/aov.h"

#include <algorithm>
#include <sstream>

#include "core/error.h"

namespace cinepath::preview {

const std::vector<AovInfo>& AovTable() {
  static const std::vector<AovInfo> table = {
      {Aov::kDepth, "depth", "Z", "m",
       "distance along the optical axis to what the pixel centre sees; +inf for sky; past the mesh's edge the "
       "distance to the ground plane (unless --backdrop none)"},
      {Aov::kBlur, "blur", "Y", "px", "the blur-circle diameter at that depth, as the rays realize it"},
      {Aov::kMask, "mask", "Y", "id",
       "the subject the pixel centre sees: its index in the plan's subjects + 1; 0 for the mesh, the ground "
       "and the sky"},
  };
  return table;
}

const std::vector<float>& AovValues(const FrameImage& frame, Aov aov) {
  switch (aov) {
    case Aov::kDepth: return frame.depth_m;
    case Aov::kBlur: return frame.blur_px;
    case Aov::kMask: return frame.subject_id;
  }
  throw InternalError("AovValues: unknown AOV");
}

std::vector<Aov> ParseAovList(const std::string& text) {
  std::vector<Aov> aovs;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    const auto& table = AovTable();
    const auto it = std::find_if(table.begin(), table.end(), [&](const AovInfo& a) { return item == a.name; });
    if (it == table.end()) {
      std::string names;
      for (const auto& a : table) names += std::string(names.empty() ? "" : ", ") + a.name;
      throw InputError("--aov: expected a comma-separated list of " + names + ", got '" + text + "'");
    }
    if (std::find(aovs.begin(), aovs.end(), it->aov) == aovs.end()) aovs.push_back(it->aov);
  }
  if (aovs.empty()) throw InputError("--aov: expected at least one of depth, blur, mask");
  std::sort(aovs.begin(), aovs.end());  // the table's order
  return aovs;
}

}  // namespace cinepath::preview
