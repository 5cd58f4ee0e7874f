// shots/plan_warnings.h: a moving actor that stops dead at its last key inside a shot that follows it.
#include "shots/plan_warnings.h"

#include <gtest/gtest.h>

#include "core/json.h"
#include "shots/team_planner.h"

namespace cinepath::shots {
namespace {

// A walker keyed at 0 and 10 s (`last` its last position) and a CHASE of it for `duration_s`.
std::vector<std::string> WarningsFor(const std::string& keys, double duration_s) {
  const Json doc = Json::parse(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30, "drone": "px4-multirotor",
    "camera": {"filmback": "super35", "min_focal_length_mm": 24, "max_focal_length_mm": 70},
    "actors": [{"name": "walker", "height_m": 1.8, "keyframes": )" +
                               keys + R"(}],
    "shots": [{"name": "follow", "type": "CHASE", "subject": "walker", "duration_s": )" +
                               std::to_string(duration_s) + R"(, "distance_m": 12, "height_m": 5}]})");
  const ShotList list = ParseShotList(doc, "test_shots.json");
  return StopsDeadWarnings(list, PlanTeam(list));
}

const char* kMidStride =
    R"([{"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 10, "position_enu_m": [15, 0, 0]}])";

TEST(PlanWarnings, AnActorStoppingDeadAtItsLastKeyInsideTheShotIsNamed) {
  const std::vector<std::string> w = WarningsFor(kMidStride, 16);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("actor \"walker\" stops dead at its last key (10 s, from 1.5 m/s)"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("shot \"follow\" follows it to 16 s"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("add a key where the actor comes to rest"), std::string::npos) << w[0];
}

TEST(PlanWarnings, NoWarningWhenTheShotEndsAtTheKeyOrTheActorComesToRest) {
  EXPECT_TRUE(WarningsFor(kMidStride, 10).empty());
  // A third key at the same place: the Catmull-Rom path slows to rest at it.
  EXPECT_TRUE(WarningsFor(R"([{"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 10, "position_enu_m": [15, 0, 0]},
                              {"time_s": 14, "position_enu_m": [15, 0, 0]}])",
                          20)
                  .empty());
  // Slower than kStopsDeadMS at the key: 2 m in 10 s.
  EXPECT_TRUE(
      WarningsFor(R"([{"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 10, "position_enu_m": [2, 0, 0]}])", 16)
          .empty());
}

}  // namespace
}  // namespace cinepath::shots
