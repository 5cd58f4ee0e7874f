// libFuzzer target: plan.json through `view`'s data step, in process: the page data of the plan about each
// of its flights (one drone is a team of one), written with the one serializer (which refuses NaN and
// infinity), with and without a WGS84 origin to show.
#include <cstddef>
#include <cstdint>
#include <optional>

#include "tests/fuzz/plan_stage_input.h"
#include "viewer/page_data.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace cinepath;
  const auto team = fuzz::ReadPlanInput(data, size);
  if (!team) return 0;
  for (const std::optional<Geodetic>& origin : {team->origin, std::optional<Geodetic>()}) {
    fuzz::RunStage([&] {
      for (size_t primary = 0; primary < team->flights.size(); ++primary) {
        DumpJson(viewer::PageDataJson(*team, primary, "plan.json", origin));
      }
    });
  }
  return 0;
}
