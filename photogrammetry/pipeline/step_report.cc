#include "photogrammetry/pipeline/step_report.h"

namespace cinepath::photogrammetry {

double StepTimer::Seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double StepTimer::RoundedSeconds() const { return RoundToDecimals(Seconds(), 3); }

void AddStepTime(Json& step, const StepTimer& timer, bool report_times) {
  if (report_times) step["time_s"] = timer.RoundedSeconds();
}

}  // namespace cinepath::photogrammetry
