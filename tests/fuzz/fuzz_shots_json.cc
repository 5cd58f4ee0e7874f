// libFuzzer target: a shot list (shots.json) parsed and planned. Bad input throws cinepath::InputError;
// anything else (a crash, a hang, another exception) is a finding.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/error.h"
#include "core/json.h"
#include "shots/planner.h"
#include "shots/shot_list.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const cinepath::Json doc =
        cinepath::ParseJsonText(std::string_view(reinterpret_cast<const char*>(data), size), "shots.json");
    const auto list = cinepath::shots::ParseShotList(doc, "shots.json");
    cinepath::shots::PlanOptions options;
    options.max_samples = 20'000;  // planning is checked, not a long plan's memory
    cinepath::shots::PlanShots(list, options);
  } catch (const cinepath::InputError&) {
  } catch (const cinepath::InfeasibleError&) {}
  return 0;
}
