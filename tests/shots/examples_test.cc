// Every shipped example (examples/*shots*.json) plans cleanly, carries a WGS84 origin, and plans
// to the same bytes twice.
#include <algorithm>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>

#include "core/plan_file.h"
#include "shots/plan_plot.h"
#include "shots/planner.h"
#include "shots/shot_list.h"

namespace cinepath::shots {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> Examples() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(fs::path(CINEPATH_SOURCE_DIR) / "examples")) {
    const std::string name = e.path().filename().string();
    if (name.find("shots") != std::string::npos && e.path().extension() == ".json") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Examples, EveryShotTypeFamilyPlans) {
  const auto examples = Examples();
  ASSERT_GE(examples.size(), 6u);
  std::set<std::string> types;
  for (const auto& path : examples) {
    SCOPED_TRACE(path.string());
    const ShotList list = ReadShotListFile(path);
    EXPECT_TRUE(list.origin.has_value()) << "every example carries a WGS84 origin";
    const Trajectory plan = PlanShots(list);
    EXPECT_FALSE(plan.samples.empty());
    // Shipped examples are flyable by their drone profile (export plans the first of them).
    EXPECT_TRUE(plan.feasibility.feasible())
        << plan.feasibility.violations.front().limit << " in shot " << plan.feasibility.violations.front().shot;
    for (const auto& s : plan.shots) types.insert(s.type);
    const std::string text = PlanToText(plan);
    EXPECT_TRUE(text == PlanToText(PlanShots(ReadShotListFile(path)))) << "not deterministic";
    // Round trip through the file format.
    EXPECT_TRUE(PlanToText(PlanFromJson(Json::parse(text), "plan.json")) == text) << "round trip changed bytes";
    EXPECT_NE(PlanToSvg(plan).find("</svg>"), std::string::npos);
  }
  for (const char* t : {"CHASE", "ORBIT", "FLYBY", "DOLLY", "CRANE", "HELIX", "DRONIE", "TOP-DOWN", "DOLLY-ZOOM",
                        "LOCKED-OFF", "KEYFRAMES"}) {
    EXPECT_TRUE(types.count(t)) << t << " has no example";
  }
}

}  // namespace
}  // namespace cinepath::shots
