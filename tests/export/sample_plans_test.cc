// The plan.json inputs of the export golden cases (tests/golden/export/<case>/plan.json) are the
// synthetic ORBIT / CHASE / FLYBY plans of sample_trajectories.h written by core/plan_file.h. This
// test keeps them in step: it fails when a checked-in plan differs from the generator, and
// CINEPATH_UPDATE_GOLDEN=1 rewrites them.
#include <cstdlib>
#include <filesystem>

#include <gtest/gtest.h>

#include "core/file_io.h"
#include "core/plan_file.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

void CheckPlanFile(const std::string& relative_path, const Trajectory& plan) {
  const std::filesystem::path path = std::filesystem::path(CINEPATH_SOURCE_DIR) / relative_path;
  const std::string text = PlanToText(plan);
  const char* update = std::getenv("CINEPATH_UPDATE_GOLDEN");
  if (update && std::string(update) == "1") {
    std::filesystem::create_directories(path.parent_path());
    WriteFileAtomic(path, text);
  }
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  EXPECT_EQ(ReadFileToString(path), text) << path << " is stale; rerun with CINEPATH_UPDATE_GOLDEN=1";
  // And it reads back into the same samples.
  const Trajectory back = ReadPlanFile(path);
  ASSERT_EQ(back.samples.size(), plan.samples.size());
  for (size_t i = 0; i < plan.samples.size(); ++i) {
    EXPECT_LT((back.samples[i].position_enu_m - plan.samples[i].position_enu_m).norm(), 1e-5);
  }
}

void CheckPlan(const std::string& case_name, const Trajectory& plan) {
  CheckPlanFile("tests/golden/export/" + case_name + "/plan.json", plan);
}

// The flyby flown twice as fast (20 m/s), at 5 Hz: over every drone's speed limit.
Trajectory FastFlyby() {
  Trajectory t = testing::FlybyPlan(12, 5);
  for (auto& s : t.samples) s.time_s *= 0.5;
  t.shots.front().end_time_s *= 0.5;
  t.frame_rate_hz = 10;
  t.drone.max_horizontal_speed_m_s = 25;
  return t;
}

// A three-sample plan; tests/export/data/bad_*.json are hand-edited copies of it.
Trajectory TinyPlan() { return testing::FlybyPlan(1, 2); }

TEST(SamplePlans, FastFlyby) { CheckPlan("fast_flyby_overspeed", FastFlyby()); }
TEST(SamplePlans, Tiny) { CheckPlanFile("tests/export/data/tiny_plan.json", TinyPlan()); }
TEST(SamplePlans, Orbit) { CheckPlan("orbit_px4", testing::OrbitPlan()); }
TEST(SamplePlans, Chase) { CheckPlan("chase_ardupilot_amsl", testing::ChasePlan()); }
TEST(SamplePlans, Flyby) { CheckPlan("flyby_px4_home", testing::FlybyPlan()); }

}  // namespace
}  // namespace cinepath::exporter
