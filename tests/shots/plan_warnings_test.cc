// shots/plan_warnings.h: an actor placed at an absolute height far off the scene's ground; a moving actor
// that stops dead at its last key inside a shot that follows it.
#include "shots/plan_warnings.h"

#include <gtest/gtest.h>

#include "core/ground.h"
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

// Level ground at up -28 m over |e|, |n| < 50 (a scene whose origin lies 28 m above its ground).
class LevelGround : public Ground {
 public:
  std::optional<double> SurfaceUpM(double e, double n, double from_up_m) const override {
    if (std::fabs(e) > 50 || std::fabs(n) > 50 || from_up_m < -28) return std::nullopt;
    return -28.0;
  }
  const std::string& source() const override { return source_; }

 private:
  std::string source_ = "level.glb";
};

std::vector<std::string> FloatingFor(const std::string& actor, bool with_ground = true) {
  const Json doc = Json::parse(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30, "drone": "px4-multirotor",
    "camera": {"filmback": "super35", "min_focal_length_mm": 24, "max_focal_length_mm": 70},
    "actors": [)" + actor + R"(],
    "shots": [{"name": "hold", "type": "ORBIT", "subject": "a", "duration_s": 2, "radius_m": 20, "height_m": 10,
               "turns": 0.05}]})");
  const ShotList list =
      ParseShotList(doc, "test_shots.json", std::nullopt, with_ground ? std::make_shared<LevelGround>() : nullptr);
  return FloatingActorWarnings(list);
}

TEST(PlanWarnings, AnActorAtAnAbsoluteHeightFarOffTheGroundIsNamed) {
  // u = 0 is the origin's height: 28 m over this scene's ground.
  std::vector<std::string> w = FloatingFor(R"({"name": "a", "position_enu_m": [6, -6, 0]})");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("actor \"a\" (test_shots.json: actors[0].position_enu_m) stands 28 m above the scene's "
                      "ground (level.glb) at (6, -6)"),
            std::string::npos)
      << w[0];
  EXPECT_NE(w[0].find("give the position without its height ([east_m, north_m]"), std::string::npos) << w[0];
  // Buried: its head 10.2 m under the surface.
  w = FloatingFor(R"({"name": "a", "position_enu_m": [6, -6, -40]})");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("has its head 10.2 m under the scene's surface"), std::string::npos) << w[0];
  // Keys: the one farthest off is named.
  w = FloatingFor(R"({"name": "a", "keyframes": [{"time_s": 0, "position_enu_m": [0, 0, -28]},
                                                 {"time_s": 1, "position_enu_m": [2, 0, -8]},
                                                 {"time_s": 2, "position_enu_m": [4, 0, -18]}]})");
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("keyframes[1].position_enu_m) stands 20 m above"), std::string::npos) << w[0];
}

TEST(PlanWarnings, NoWarningOnTheGroundNearItOffTheMeshOrWithoutAScene) {
  EXPECT_TRUE(FloatingFor(R"({"name": "a", "position_enu_m": [6, -6]})").empty());
  EXPECT_TRUE(FloatingFor(R"({"name": "a", "position_enu_m": [6, -6], "above_ground_m": 10})").empty());
  EXPECT_TRUE(FloatingFor(R"({"name": "a", "position_enu_m": [6, -6, -25.5]})").empty());  // 2.5 m up: a roof
  EXPECT_TRUE(FloatingFor(R"({"name": "a", "position_enu_m": [80, 0, 0]})").empty());      // no mesh there
  EXPECT_TRUE(FloatingFor(R"({"name": "a", "position_enu_m": [6, -6, 0]})", false).empty());
  // Kept on the ground: its keys' heights are not used.
  const std::string kept = R"({"name": "a", "on_ground": true,
    "keyframes": [{"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 1, "position_enu_m": [2, 0, 0]}]})";
  EXPECT_TRUE(FloatingFor(kept).empty());
}

}  // namespace
}  // namespace cinepath::shots
