// libFuzzer target: plan.json through `optimize`'s problem set-up, in process: the plan split into knots,
// every cost term added (draft preset, no scene), then in place of Ceres' solve one evaluation of the
// problem at the plan as given, which must give a finite cost, residuals and gradient (a non-finite one is
// what makes the solver fail with exit 1), and the report and the plan written back.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <ceres/ceres.h>

#include "optimizer/optimize_options.h"
#include "optimizer/team_optimizer.h"
#include "tests/fuzz/plan_stage_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace cinepath;
  auto team = fuzz::ReadPlanInput(data, size);
  if (!team) return 0;
  optimizer::OptimizeOptions options = optimizer::OptimizeOptions::ForQuality(Quality::kDraft);
  options.visibility_rounds = 1;
  options.external_solver = [](ceres::Problem* problem, const std::vector<double*>&,
                               const std::vector<std::vector<int>>&) {
    double cost = 0;
    std::vector<double> residuals, gradient;
    const bool ok = problem->Evaluate(ceres::Problem::EvaluateOptions(), &cost, &residuals, &gradient, nullptr);
    if (!ok || !std::isfinite(cost)) __builtin_trap();
    for (double v : residuals) {
      if (!std::isfinite(v)) __builtin_trap();
    }
    for (double v : gradient) {
      if (!std::isfinite(v)) __builtin_trap();
    }
    return 0;
  };
  optimizer::TeamOptimizeInput input;
  input.plan = std::move(*team);
  fuzz::RunStage([&] {
    const optimizer::TeamOptimizeResult result = optimizer::OptimizeTeam(input, options);
    TeamPlanToText(result.plan);
    DumpJson(result.report);
  });
  return 0;
}
