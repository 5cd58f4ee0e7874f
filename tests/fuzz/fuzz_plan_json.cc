// libFuzzer target: plan.json read back (what optimize, render, export and view read), then written again.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "core/json.h"
#include "core/plan_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const cinepath::Json doc =
        cinepath::ParseJsonText(std::string_view(reinterpret_cast<const char*>(data), size), "plan.json");
    const cinepath::Trajectory plan = cinepath::PlanFromJson(doc, "plan.json");
    cinepath::PlanToText(plan);
  } catch (const cinepath::InputError&) {}
  return 0;
}
