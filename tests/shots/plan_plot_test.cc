#include "shots/plan_plot.h"

#include <gtest/gtest.h>

#include "shots/planner.h"

namespace cinepath::shots {
namespace {

size_t Count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(PlanPlot, PanelsFrustumsAndDeterminism) {
  const ShotList list = ParseShotList(Json::parse(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 10,
      "camera": {"filmback": "super35", "min_focal_length_mm": 24},
      "actors": [{"name": "hero <1>", "position_enu_m": [0, 0, 0]}],
      "shots": [{"name": "o", "type": "ORBIT", "subject": "hero <1>", "duration_s": 20, "radius_m": 20,
        "height_m": 5, "turns": 1}]})"),
                                      "shots.json");
  const Trajectory plan = PlanShots(list);
  const std::string svg = PlanToSvg(plan);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(Count(svg, "Top-down"), 1u);
  EXPECT_EQ(Count(svg, "Side (looking north)"), 1u);
  EXPECT_EQ(Count(svg, "Focal length (log scale)"), 1u);
  // 20 s plan, 201 samples: 10 frustums (every 20 samples; 201 / 10), two wedges each.
  EXPECT_EQ(Count(svg, "<polygon"), 2u * 11u);
  EXPECT_NE(svg.find("hero &lt;1&gt;"), std::string::npos);  // names are escaped
  EXPECT_EQ(svg, PlanToSvg(PlanShots(list)));
}

}  // namespace
}  // namespace cinepath::shots
