#include "viewer/page_data.h"

#include <limits>

#include <gtest/gtest.h>

namespace cinepath::viewer {
namespace {

// Two shots of three samples at 1 Hz, moving 2 m east per second; the second starts with a cut, 100 m away.
Trajectory TwoShots() {
  Trajectory plan;
  plan.frame_rate_hz = 1;
  plan.shots = {{.name = "a", .type = "FLYBY", .start_time_s = 0, .end_time_s = 2},
                {.name = "b", .type = "ORBIT", .start_time_s = 3, .end_time_s = 5, .transition = "cut"}};
  for (int k = 0; k < 6; ++k) {
    TrajectorySample s;
    s.time_s = k;
    s.position_enu_m = {2.0 * k + (k >= 3 ? 100 : 0), 0, 10};
    s.shot = k < 3 ? "a" : "b";
    s.focus_distance_m = k == 5 ? std::numeric_limits<double>::infinity() : 20;
    plan.samples.push_back(s);
  }
  return plan;
}

// A plan as `view` reads it: a team, here of one flight (a "cinepath.plan/1" file).
TeamPlan TeamOf(std::vector<Trajectory> plans) {
  TeamPlan team;
  team.single = plans.size() == 1;
  for (size_t f = 0; f < plans.size(); ++f) {
    team.flights.push_back({"drone" + std::to_string(f), std::nullopt, std::move(plans[f])});
  }
  return team;
}

TEST(PageData, CutsBreakThePathAndTheSpeeds) {
  const Trajectory plan = TwoShots();
  const std::vector<bool> cuts = CutBeforeSamples(plan);
  EXPECT_EQ(cuts, (std::vector<bool>{false, false, false, true, false, false}));
  for (double v : SampleSpeedsMps(plan)) EXPECT_DOUBLE_EQ(v, 2.0);  // not 100 m in a second across the cut
}

TEST(PageData, ContinuousShotsAreNotCuts) {
  Trajectory plan = TwoShots();
  plan.shots[1].transition = "continuous";
  EXPECT_EQ(CutBeforeSamples(plan), std::vector<bool>(6, false));
}

TEST(PageData, JsonInThreeJsFrameWithInfinityAsNull) {
  Trajectory plan = TwoShots();
  plan.feasibility.violations.push_back({"horizontal_speed", "b", 3, 4, 20, 15, "m/s"});
  const Json data = PageDataJson(TeamOf({plan}), 0, "plan.json", std::nullopt);
  EXPECT_TRUE(data["origin"].is_null());
  EXPECT_EQ(data["format"], "cinepath.previs/1");
  const Json& s = data["samples"];
  ASSERT_EQ(s["time_s"].size(), 6u);
  EXPECT_EQ(s["position_m"].size(), 18u);
  EXPECT_EQ(s["position_m"][1], 10.0);  // up is three.js's y
  EXPECT_EQ(s["position_m"][2], -0.0);  // north 0 -> z 0
  EXPECT_EQ(s["quaternion"].size(), 24u);
  EXPECT_EQ(s["focus_distance_m"][0], 20.0);
  EXPECT_TRUE(s["focus_distance_m"][5].is_null());
  EXPECT_EQ(s["shot"][4], 1);
  EXPECT_EQ(data["cuts_before_sample"], Json::array({3}));
  EXPECT_EQ(data["violations"][0]["limit"], "horizontal_speed");
  // A team of one: its one flight, whose samples are the page's own (not written twice), no edit.
  const Json& team = data["team"];
  ASSERT_EQ(team["flights"].size(), 1u);
  EXPECT_EQ(team["primary"], 0);
  EXPECT_EQ(team["flights"][0]["name"], "drone0");
  EXPECT_EQ(team["flights"][0]["cuts_before_sample"], Json::array({3}));
  EXPECT_FALSE(team["flights"][0].contains("position_m"));
  EXPECT_TRUE(team["edit"].empty());
  EXPECT_TRUE(team["conflicts"].empty());
}

// Several drones: the primary's detail as for one, and every other flight with its own samples.
TEST(PageData, EveryFlightOfATeamAboutItsPrimary) {
  Trajectory other = TwoShots();
  other.samples.resize(4);
  for (auto& s : other.samples) {
    s.position_enu_m.y() += 30;  // 30 m north
    s.focal_length_mm = 85;      // its own lens, which its camera view reads
    s.f_number = 5.6;
  }
  other.feasibility.violations.push_back({"terrain_clearance", "a", 0, 1, 1.2, 3, "m"});
  Keyframe key;
  key.shot = "a";
  key.time_s = 1;
  key.position_enu_m = {1, 30, 10};
  other.keyframes.push_back(key);
  TeamPlan team = TeamOf({other, TwoShots()});
  team.edit.push_back({.at_s = 1, .drone = "drone1"});
  const Json data = PageDataJson(team, 1, "plan.json", std::nullopt);
  EXPECT_EQ(data["samples"]["time_s"].size(), 6u);  // the primary's detail
  const Json& flights = data["team"]["flights"];
  ASSERT_EQ(flights.size(), 2u);
  EXPECT_EQ(flights[0]["time_s"].size(), 4u);
  EXPECT_EQ(flights[0]["position_m"][2], -30.0);  // north is three.js's -z
  EXPECT_EQ(flights[0]["focal_length_mm"][3], 85.0);
  EXPECT_EQ(flights[0]["f_number"][3], 5.6);
  EXPECT_NE(data["samples"]["focal_length_mm"][3], 85.0);
  EXPECT_NE(flights[0]["colour"], flights[1]["colour"]);
  EXPECT_FALSE(flights[1].contains("position_m"));
  EXPECT_EQ(data["team"]["edit"][0]["drone"], "drone1");
  // The other flight's shots with their times and its broken limits, for its lens graphs and the
  // feasibility box (a minimum is marked, to be written "<").
  ASSERT_EQ(flights[0]["shot_spans"].size(), 2u);
  EXPECT_EQ(flights[0]["shot_spans"][1]["start_time_s"], 3.0);
  ASSERT_EQ(flights[0]["keyframes"].size(), 1u);
  EXPECT_EQ(flights[0]["keyframes"][0]["position_m"][2], -30.0);
  EXPECT_FALSE(flights[1].contains("keyframes"));  // the primary's are the page's own
  ASSERT_EQ(flights[0]["violations"].size(), 1u);
  EXPECT_EQ(flights[0]["violations"][0]["limit"], "terrain_clearance");
  EXPECT_EQ(flights[0]["violations"][0]["minimum"], true);
  EXPECT_TRUE(data["violations"].empty());  // the primary's own
}

TEST(PageData, OriginWhenKnown) {
  const Json data = PageDataJson(TeamOf({TwoShots()}), 0, "plan.json", Geodetic{50.8, -0.14, 50});
  EXPECT_DOUBLE_EQ(data["origin"]["lat_deg"].get<double>(), 50.8);
}

}  // namespace
}  // namespace cinepath::viewer
