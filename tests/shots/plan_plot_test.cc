#include "shots/plan_plot.h"

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>

#include "shots/planner.h"
#include "shots/team_planner.h"

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

// Two drones orbiting one actor half a turn apart with a wide lens: each sees the other (in_shot conflicts).
TeamPlan WideOrbitTeam() {
  const ShotList list = ParseShotList(Json::parse(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 10,
      "camera": {"filmback": "super35", "min_focal_length_mm": 12},
      "drone": "px4-multirotor",
      "drones": [{"name": "north", "home_enu_m": [0, 30, 0]}, {"name": "south", "home_enu_m": [0, -30, 0]}],
      "actors": [{"name": "hero", "position_enu_m": [0, 0, 0]}],
      "shots": [{"name": "a", "drone": "north", "type": "ORBIT", "subject": "hero", "duration_s": 20,
                 "radius_m": 20, "height_m": 5, "turns": 1, "start_bearing_deg": 0, "lens": {"focal_length_mm": 12}},
                {"name": "b", "drone": "south", "type": "ORBIT", "subject": "hero", "duration_s": 20,
                 "radius_m": 20, "height_m": 5, "turns": 1, "start_bearing_deg": 180, "lens": {"focal_length_mm": 12}}],
      "edit": [{"at_s": 0, "drone": "north"}, {"at_s": 10, "drone": "south", "match_focus": true}]})"),
                                      "shots.json");
  return PlanTeam(list);
}

TEST(PlanPlot, TeamDrawsOnePathPerDroneInItsColourAndShadesEveryConflict) {
  TeamPlan plan = WideOrbitTeam();
  ASSERT_EQ(plan.flights.size(), 2u);
  // The wide lens puts each drone in the other's live shot; add a separation breach so both kinds show.
  ASSERT_FALSE(plan.team.conflicts.empty());
  TeamConflict breach;
  breach.limit = "separation";
  breach.drone = "north";
  breach.other = "south";
  breach.start_time_s = 3;
  breach.end_time_s = 4.5;
  breach.worst_value = 2.5;
  breach.limit_value = 5;
  breach.unit = "m";
  plan.team.conflicts.push_back(breach);
  const std::string svg = PlanToSvg(plan);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");

  // One path per drone in each of the two views, each drone in one colour, the two colours distinct.
  const std::regex path_re("class=\"flight\" data-drone=\"([a-z]+)\" stroke=\"(#[0-9a-f]{6})\"");
  std::map<std::string, std::set<std::string>> colours;
  size_t paths = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), path_re); it != std::sregex_iterator(); ++it) {
    colours[(*it)[1]].insert((*it)[2]);
    ++paths;
  }
  EXPECT_EQ(paths, 4u);
  ASSERT_EQ(colours.size(), 2u);
  ASSERT_EQ(colours["north"].size(), 1u);
  ASSERT_EQ(colours["south"].size(), 1u);
  EXPECT_NE(*colours["north"].begin(), *colours["south"].begin());

  // A shaded rect per conflict range on each of the three time panels, at the conflict's times.
  EXPECT_EQ(Count(svg, "class=\"conflict\""), 3u * plan.team.conflicts.size());
  EXPECT_EQ(Count(svg, "class=\"conflict\" data-limit=\"separation\""), 3u);
  EXPECT_EQ(Count(svg, "class=\"conflict\" data-limit=\"in_shot\""), 3u * (plan.team.conflicts.size() - 1));
  EXPECT_NE(svg.find("north-south 2.50 m apart"), std::string::npos);  // labelled
  EXPECT_NE(svg.find("'s shot ("), std::string::npos);                 // in_shot labelled
  // The edit's two cuts, and the legend names both drones.
  EXPECT_EQ(Count(svg, "class=\"edit\""), 2u);
  EXPECT_NE(svg.find(">north (px4-multirotor, 1 shot)<"), std::string::npos);
  EXPECT_NE(svg.find(">south (px4-multirotor, 1 shot)<"), std::string::npos);
  EXPECT_EQ(svg, PlanToSvg(plan));  // deterministic
}

// Every drone's broken limits show on the team's plot (shaded over both lens panels, named on the focal one,
// counted in the legend), not only the conflicts between drones.
TEST(PlanPlot, TeamShadesEveryDronesBrokenLimits) {
  TeamPlan plan = WideOrbitTeam();
  ASSERT_EQ(plan.flights.size(), 2u);
  const int south = plan.FindFlight("south");
  ASSERT_GE(south, 0);
  FeasibilityViolation v;
  v.limit = "altitude_min";
  v.shot = plan.flights[south].plan.shots.at(0).name;
  v.start_time_s = 0;
  v.end_time_s = 1.5;
  v.worst_value = -2;
  v.limit_value = 1;
  v.unit = "m";
  plan.flights[south].plan.feasibility.violations = {v};
  for (auto& flight : plan.flights) {
    if (flight.name != "south") flight.plan.feasibility.violations.clear();
  }
  const std::string svg = PlanToSvg(plan);
  EXPECT_EQ(Count(svg, "class=\"violation\" data-drone=\"south\" data-limit=\"altitude_min\""), 2u);
  EXPECT_EQ(Count(svg, "class=\"violation\""), 2u);
  EXPECT_NE(svg.find(">south: altitude_min<"), std::string::npos);
  EXPECT_NE(svg.find(">south (px4-multirotor, 1 shot, 1 broken limit range)<"), std::string::npos);
  EXPECT_NE(svg.find(">north (px4-multirotor, 1 shot)<"), std::string::npos);
}

TEST(PlanPlot, AVersionOnePlanDrawsAsBefore) {
  const ShotList list = ParseShotList(Json::parse(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 10,
      "camera": {"filmback": "super35", "min_focal_length_mm": 24},
      "actors": [{"name": "hero", "position_enu_m": [0, 0, 0]}],
      "shots": [{"name": "o", "type": "ORBIT", "subject": "hero", "duration_s": 10, "radius_m": 20,
        "height_m": 5, "turns": 1}]})"),
                                      "shots.json");
  // A version 1 plan read as a team (core/plan_file.h): one flight, `single` set.
  TeamPlan team;
  team.single = true;
  team.flights.push_back({"px4-multirotor", std::nullopt, PlanShots(list)});
  EXPECT_EQ(PlanToSvg(team), PlanToSvg(PlanShots(list)));
  EXPECT_EQ(PlanToSvg(team).find("class=\"flight\""), std::string::npos);
}

}  // namespace
}  // namespace cinepath::shots
