// Shots on the terrain (plan --scene): heights above the ground, actors kept on it, camera heights
// measured from it, and the terrain clearance check, against a ground given in closed form.
#include <cmath>

#include <gtest/gtest.h>

#include "shots/planner.h"
#include "shots/shot_list.h"
#include "tests/support/input_error.h"

namespace cinepath::shots {
namespace {

// A slope rising 0.1 m per metre east, with a 5 m plateau east of e = 40 and nothing beyond |n| > 200.
class SlopeGround : public Ground {
 public:
  std::optional<double> SurfaceUpM(double e, double n, double from_up_m) const override {
    if (std::fabs(n) > 200) return std::nullopt;
    const double up = e > 40 ? 5.0 + 0.1 * e : 0.1 * e;
    if (up > from_up_m) return std::nullopt;
    return up;
  }
  const std::string& source() const override { return source_; }

 private:
  std::string source_ = "slope.glb";
};

Json Doc(const std::string& actors, const std::string& shots) {
  return Json::parse(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 10,
    "camera": {"filmback": "super35", "min_focal_length_mm": 24, "max_focal_length_mm": 70},
    "drone": "px4-multirotor", "actors": )" +
                     actors + R"(, "shots": )" + shots + "}");
}

const std::shared_ptr<const Ground> kGround = std::make_shared<SlopeGround>();

TEST(Terrain, PositionsAboveTheGround) {
  const ShotList list = ParseShotList(
      Doc(R"([{"name": "a", "position_enu_m": [10, 0], "above_ground_m": 0.5},
              {"name": "b", "position_enu_m": [20, 5]}])",
          R"([{"type": "ORBIT", "subject": "a", "duration_s": 1, "radius_m": 10, "height_m": 5, "turns": 0.1}])"),
      "shots.json", std::nullopt, kGround);
  EXPECT_NEAR(list.actors[0].PositionAt(0).z(), 1.0 + 0.5, 1e-12);
  EXPECT_NEAR(list.actors[1].PositionAt(0).z(), 2.0, 1e-12);
}

TEST(Terrain, AnActorOnTheGroundFollowsItAtEverySample) {
  // Keys at e = 0 and e = 80: the straight line between them would cut under the plateau.
  const ShotList list = ParseShotList(
      Doc(R"([{"name": "walker", "on_ground": true, "interpolation": "linear",
               "keyframes": [{"time_s": 0, "position_enu_m": [0, 0]}, {"time_s": 8, "position_enu_m": [80, 0]}]}])",
          R"([{"type": "CHASE", "subject": "walker", "duration_s": 8, "distance_m": 10, "height_m": 6}])"),
      "shots.json", std::nullopt, kGround);
  const Trajectory plan = PlanShots(list);
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    const Eigen::Vector3d p = plan.subjects[0].positions_enu_m[k];
    EXPECT_NEAR(p.z(), *kGround->SurfaceUpM(p.x(), p.y()), 1e-9) << "t=" << plan.samples[k].time_s;
  }
}

TEST(Terrain, KeysAllOnTheGroundKeepTheActorOnItBetweenThem) {
  // The same keys without "on_ground": every key stands 0.3 m above the ground, so the actor does too at
  // every sample (the line between the keys passes under the plateau). "on_ground": false keeps the line.
  const std::string keys = R"("interpolation": "linear", "keyframes": [
      {"time_s": 0, "position_enu_m": [0, 0], "above_ground_m": 0.3},
      {"time_s": 8, "position_enu_m": [80, 0], "above_ground_m": 0.3}]}])";
  const std::string shots = R"([{"type": "CHASE", "subject": "walker", "duration_s": 8, "distance_m": 10,
      "height_m": 6}])";
  const Trajectory implied =
      PlanShots(ParseShotList(Doc(R"([{"name": "walker", )" + keys, shots), "shots.json", std::nullopt, kGround));
  const Trajectory line = PlanShots(ParseShotList(Doc(R"([{"name": "walker", "on_ground": false, )" + keys, shots),
                                                  "shots.json", std::nullopt, kGround));
  double most_below = 0;
  for (size_t k = 0; k < implied.samples.size(); ++k) {
    const Eigen::Vector3d p = implied.subjects[0].positions_enu_m[k];
    EXPECT_NEAR(p.z(), *kGround->SurfaceUpM(p.x(), p.y()) + 0.3, 1e-9) << "t=" << implied.samples[k].time_s;
    const Eigen::Vector3d q = line.subjects[0].positions_enu_m[k];
    most_below = std::max(most_below, *kGround->SurfaceUpM(q.x(), q.y()) + 0.3 - q.z());
  }
  EXPECT_GT(most_below, 1.0);  // the line cuts under the plateau, as asked
  // Keys at different heights above the ground, or one absolute key, keep the spline.
  const Trajectory mixed = PlanShots(ParseShotList(Doc(R"([{"name": "walker", "interpolation": "linear", "keyframes": [
          {"time_s": 0, "position_enu_m": [0, 0]}, {"time_s": 8, "position_enu_m": [80, 0, 13]}]}])",
                                                       shots),
                                                   "shots.json", std::nullopt, kGround));
  EXPECT_NEAR(mixed.subjects[0].positions_enu_m[mixed.samples.size() / 2].z(), 6.5, 1e-6);
}

// Photogrammetry ground: a gentle slope under centimetre noise, a vertex every half metre (each a kink).
class NoisyGround : public Ground {
 public:
  std::optional<double> SurfaceUpM(double e, double /*n*/, double from_up_m) const override {
    const double cell = std::floor(e / 0.5), w = e / 0.5 - cell;
    const double up = 0.05 * e + (1 - w) * Noise(cell) + w * Noise(cell + 1);
    if (up > from_up_m) return std::nullopt;
    return up;
  }
  const std::string& source() const override { return source_; }

 private:
  static double Noise(double cell) { return 0.03 * std::sin(cell * 12.9898 + std::sin(cell * 78.233) * 43.7); }
  std::string source_ = "noisy.glb";
};

// The third difference of a height track at the plan's frame rate: its worst jerk, m/s^3.
double WorstVerticalJerk(const std::vector<double>& up_m, double dt) {
  double worst = 0;
  for (size_t k = 3; k < up_m.size(); ++k) {
    worst = std::max(worst, std::fabs(up_m[k] - 3 * up_m[k - 1] + 3 * up_m[k - 2] - up_m[k - 3]) / (dt * dt * dt));
  }
  return worst;
}

// A walker on that ground, chased 3 m above: the actor's base copies every kink (a jerk of tens of m/s^3
// at 10 frames/s, hundreds at 30), the camera flies the ground's trend (bug 2026-11-29: a chase over an
// oblique scene's mesh broke the jerk limit by thousands of m/s^3), within centimetres of 3 m above the
// walker's feet.
TEST(Terrain, ACameraChasingAnActorOnNoisyGroundFliesItsTrendNotItsBumps) {
  const auto ground = std::make_shared<NoisyGround>();
  const ShotList list = ParseShotList(
      Doc(R"([{"name": "walker", "on_ground": true, "interpolation": "linear",
               "keyframes": [{"time_s": 0, "position_enu_m": [0, 0]}, {"time_s": 20, "position_enu_m": [30, 0]}]}])",
          R"([{"type": "CHASE", "subject": "walker", "duration_s": 20, "distance_m": 6, "height_m": 3}])"),
      "shots.json", std::nullopt, ground);
  const Trajectory plan = PlanShots(list);
  std::vector<double> camera_up_m, walker_up_m;
  double worst_offset_m = 0;
  for (size_t k = 0; k < plan.samples.size(); ++k) {
    const double t = plan.samples[k].time_s;
    camera_up_m.push_back(plan.samples[k].position_enu_m.z());
    walker_up_m.push_back(list.actors[0].PositionAt(t).z());
    if (t > 0.5 && t < 19.5) {
      // The chase places the camera 3 m above the walker's (smoothed) base, 6 m behind it.
      worst_offset_m = std::max(worst_offset_m, std::fabs(camera_up_m.back() - 3.0 - walker_up_m.back()));
    }
  }
  const double dt = 0.1;                                // the document's 10 frames/s
  EXPECT_GT(WorstVerticalJerk(walker_up_m, dt), 20.0);  // the ground's kinks are there to be copied
  EXPECT_LT(WorstVerticalJerk(camera_up_m, dt), 4.0);   // px4-multirotor's jerk limit
  EXPECT_LT(worst_offset_m, 0.1);
}

TEST(Terrain, CameraHeightAboveTheGroundUnderTheCamera) {
  const ShotList list =
      ParseShotList(Doc(R"([{"name": "a", "position_enu_m": [0, 0, 0]}])",
                        R"([{"type": "FLYBY", "subject": "a", "duration_s": 8, "closest_distance_m": 10, "height_m": 12,
               "speed_m_s": 10, "travel_bearing_deg": 90, "height_reference": "ground"}])"),
                    "shots.json", std::nullopt, kGround);
  const Trajectory plan = PlanShots(list);
  for (const auto& s : plan.samples) {
    const Eigen::Vector3d& p = s.position_enu_m;
    EXPECT_NEAR(p.z() - *kGround->SurfaceUpM(p.x(), p.y()), 12.0, 1e-9) << "t=" << s.time_s;
  }
  EXPECT_TRUE(plan.feasibility.skipped.empty());
}

TEST(Terrain, ClearanceIsCheckedAgainstTheMeshOrSaidToBeSkipped) {
  // The camera flies east at 6 m above the actor's base at e = 0, into the slope and the plateau.
  const std::string actors = R"([{"name": "a", "position_enu_m": [0, 0, 0]}])";
  const std::string shots = R"([{"type": "FLYBY", "subject": "a", "duration_s": 10, "closest_distance_m": 10,
                                 "height_m": 6, "speed_m_s": 10, "travel_bearing_deg": 90, "closest_at_s": 0}])";
  const Trajectory on_mesh = PlanShots(ParseShotList(Doc(actors, shots), "shots.json", std::nullopt, kGround));
  bool found = false;
  for (const auto& v : on_mesh.feasibility.violations) {
    if (v.limit != "terrain_clearance") continue;
    found = true;
    EXPECT_EQ(v.unit, "m");
    EXPECT_EQ(v.limit_value, 3.0);
    // Above e = 30 the slope is within 3 m of the camera: the worst is under the plateau, e = 100.
    EXPECT_NEAR(v.start_time_s, 3.1, 0.11);
    EXPECT_NEAR(v.worst_value, 6.0 - 15.0, 1e-6);
  }
  EXPECT_TRUE(found);
  const Trajectory no_mesh = PlanShots(ParseShotList(Doc(actors, shots), "shots.json"));
  ASSERT_EQ(no_mesh.feasibility.skipped.size(), 1u);
  EXPECT_EQ(no_mesh.feasibility.skipped[0], "terrain_clearance: no scene mesh to check against");
}

TEST(Terrain, GroundKeysNeedTheMesh) {
  EXPECT_EQ(testing::InputErrorMessage([] {
              ParseShotList(Doc(R"([{"name": "a", "position_enu_m": [0, 0, 0]}])",
                                R"([{"type": "ORBIT", "subject": "a", "duration_s": 1, "radius_m": 5, "height_m": 5,
                                     "turns": 0.1, "height_reference": "ground"}])"),
                            "shots.json");
            }),
            "shots.json: shots[0].height_reference: \"ground\" needs the scene's mesh (`scene_mesh`)");
  EXPECT_EQ(testing::InputErrorMessage([] {
              ParseShotList(Doc(R"([{"name": "a", "on_ground": true, "position_enu_m": [0, 0, 0]}])",
                                R"([{"type": "ORBIT", "subject": "a", "duration_s": 1, "radius_m": 5, "height_m": 5,
                                     "turns": 0.1}])"),
                            "shots.json");
            }),
            "shots.json: actors[0].on_ground: needs the scene's mesh (`scene_mesh`)");
  // Off the mesh.
  EXPECT_EQ(testing::InputErrorMessage([] {
              ParseShotList(Doc(R"([{"name": "a", "position_enu_m": [0, 500]}])",
                                R"([{"type": "ORBIT", "subject": "a", "duration_s": 1, "radius_m": 5, "height_m": 5,
                                     "turns": 0.1}])"),
                            "shots.json", std::nullopt, kGround);
            }),
            "shots.json: actors[0].position_enu_m: no ground at this position: it lies outside slope.glb");
}

}  // namespace
}  // namespace cinepath::shots
