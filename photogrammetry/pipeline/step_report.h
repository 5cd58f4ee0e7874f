// The time of a step in a pipeline report (surface_pipeline.cc, mesh_texture.cc, build_scene.cc): one
// timer and one rule for writing it. Times are the only field of a report that changes from run to run, so
// each goes in only when the caller asks for times (report_times false for golden tests), rounded to the
// millisecond.
#pragma once

#include <chrono>

#include "core/json.h"

namespace cinepath::photogrammetry {

// Wall-clock seconds since construction or the last Restart().
class StepTimer {
 public:
  StepTimer() : start_(std::chrono::steady_clock::now()) {}
  void Restart() { start_ = std::chrono::steady_clock::now(); }
  double Seconds() const;
  // Seconds rounded to the millisecond, as every report prints them.
  double RoundedSeconds() const;

 private:
  std::chrono::steady_clock::time_point start_;
};

// A step's report entry gets "time_s" (rounded seconds), only when times are reported.
void AddStepTime(Json& step, const StepTimer& timer, bool report_times);

}  // namespace cinepath::photogrammetry
