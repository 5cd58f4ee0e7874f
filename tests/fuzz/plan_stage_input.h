// The input of the plan-stage targets (fuzz_plan_export, fuzz_plan_render, fuzz_plan_optimize,
// fuzz_plan_view): the bytes read as plan.json exactly as the commands read it (either version). A plan the
// reader refuses is the end of that input (exit 2); one it accepts goes on into the stage's preparation,
// where only InputError (exit 2) and InfeasibleError (exit 3) may end it: anything else escapes the target
// and libFuzzer reports it, because the command would exit 1 on a plan it should have refused or handled.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "core/error.h"
#include "core/json.h"
#include "core/plan_file.h"

namespace cinepath::fuzz {

inline std::optional<TeamPlan> ReadPlanInput(const uint8_t* data, size_t size) {
  try {
    const Json doc = ParseJsonText(std::string_view(reinterpret_cast<const char*>(data), size), "plan.json");
    return TeamPlanFromJson(doc, "plan.json");
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// Runs `stage`; the refusals a command maps to exit 2 and 3 end it quietly.
template <class Stage>
void RunStage(Stage&& stage) {
  try {
    stage();
  } catch (const InputError&) {
  } catch (const InfeasibleError&) {}
}

}  // namespace cinepath::fuzz
