#include "shots/actor.h"

#include <gtest/gtest.h>

#include "core/angles.h"
#include "core/error.h"

namespace cinepath::shots {
namespace {

TEST(Actor, StaticAndKeyframed) {
  const Json doc = Json::parse(R"([
    {"name": "a", "height_m": 2, "heading_deg": 270, "position_enu_m": [1, 2, 3]},
    {"name": "b", "interpolation": "linear", "keyframes": [{"time_s": 0, "position_enu_m": [0, 0, 0]},
                                                          {"time_s": 10, "position_enu_m": [0, 50, 0]}]}])");
  const JsonField f(doc, "shots.json", "actors");
  const Actor a = ParseActor(f.At(0), nullptr);
  EXPECT_EQ(a.PositionAt(123), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(a.AimPointAt(0), Eigen::Vector3d(1, 2, 4));
  EXPECT_EQ(a.TravelHeadingDegAt(5), 270.0);  // still: its stated heading
  const Actor b = ParseActor(f.At(1), nullptr);
  EXPECT_NEAR((b.PositionAt(5) - Eigen::Vector3d(0, 25, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(b.TravelHeadingDegAt(5), 0.0, 1e-9);   // moving north
  EXPECT_NEAR(b.TravelHeadingDegAt(-3), 0.0, 1e-9);  // before the first key: the start heading holds
  EXPECT_NEAR(b.PositionAt(20).y(), 50.0, 1e-12);    // holds after the last key
  EXPECT_DOUBLE_EQ(b.height_m(), 1.8);
}

// Largest |third difference| / dt^3 of f over [from, to] at dt = 1/30 s (the plan's jerk, as the feasibility check
// takes it from its samples).
template <typename F>
double MostJerk(F f, double from_s, double to_s) {
  const double dt = 1.0 / 30;
  double most = 0;
  for (double t = from_s; t + 3 * dt <= to_s; t += dt) {
    const Eigen::Vector3d j = (f(t + 3 * dt) - 3 * f(t + 2 * dt) + 3 * f(t + dt) - f(t)) / (dt * dt * dt);
    most = std::max(most, j.norm());
  }
  return most;
}

// A Catmull-Rom walker turning at its keys is C1 there: its acceleration steps, and a camera placed rigidly from
// it (or metres beside its direction of travel) copied each step as a jerk spike. The camera's base and heading
// are the walker's averaged over two seconds through C2 splines: finite jerk, within centimetres of the walker.
TEST(Actor, TheCameraFrameOfAWalkerTurningAtItsKeysIsSmooth) {
  const Json doc = Json::parse(R"({"name": "w", "interpolation": "catmull_rom", "keyframes": [
      {"time_s": 0, "position_enu_m": [-20, -12, 0]}, {"time_s": 6, "position_enu_m": [-8, -12, 0]},
      {"time_s": 12, "position_enu_m": [4, -10, 0]}, {"time_s": 18, "position_enu_m": [12, -2, 0]},
      {"time_s": 24, "position_enu_m": [14, 10, 0]}]})");
  const Actor w = ParseActor(JsonField(doc, "shots.json", "actors[0]"), nullptr);
  const auto keyed = [&](double t) { return w.PositionAt(t); };
  const auto base = [&](double t) { return w.CameraBaseAt(t); };
  // 8 m behind the direction of travel, as a CHASE places its camera.
  const auto chase = [&](double t) {
    const double b = RadFromDeg(w.CameraTravelHeadingDegAt(t));
    return Eigen::Vector3d(w.CameraBaseAt(t) - 8.0 * Eigen::Vector3d(std::sin(b), std::cos(b), 0));
  };
  const auto rigid_chase = [&](double t) {
    const double b = RadFromDeg(w.TravelHeadingDegAt(t));
    return Eigen::Vector3d(w.PositionAt(t) - 8.0 * Eigen::Vector3d(std::sin(b), std::cos(b), 0));
  };
  EXPECT_GT(MostJerk(keyed, 1, 23), 2.5) << "the keyed path's acceleration steps at its keys";
  EXPECT_GT(MostJerk(rigid_chase, 1, 23), 20.0);
  EXPECT_LT(MostJerk(base, 1, 23), 1.0);
  EXPECT_LT(MostJerk(chase, 1, 23), 2.0);
  for (double t = 1; t <= 23; t += 0.25) {
    EXPECT_LT((w.CameraBaseAt(t) - w.PositionAt(t)).norm(), 0.05) << t;
    EXPECT_LT(std::fabs(AngleDiffDeg(w.CameraTravelHeadingDegAt(t), w.TravelHeadingDegAt(t))), 5.0) << t;
  }
  // At the ends the base is the walker (its path runs on at its end velocity for the averages), and at rest too.
  EXPECT_LT((w.CameraBaseAt(0) - w.PositionAt(0)).norm(), 0.05);
  EXPECT_LT((w.CameraBaseAt(24) - w.PositionAt(24)).norm(), 0.05);
  EXPECT_NEAR((w.CameraBaseAt(30) - w.CameraBaseAt(24)).norm(), 0, 1e-12) << "holds after the last key";
}

// A still actor, and one that only stands, keep their camera frame exactly.
TEST(Actor, AStillActorIsItsOwnCameraBase) {
  const Json doc = Json::parse(R"([{"name": "s", "heading_deg": 30, "keyframes": [
      {"time_s": 0, "position_enu_m": [3, 4, 5]}, {"time_s": 9, "position_enu_m": [3, 4, 5]}]}])");
  const Actor a = ParseActor(JsonField(doc, "shots.json", "actors").At(0), nullptr);
  for (double t : {-1.0, 0.0, 4.5, 9.0, 12.0}) {
    EXPECT_EQ(a.CameraBaseAt(t), Eigen::Vector3d(3, 4, 5));
    EXPECT_EQ(a.CameraTravelHeadingDegAt(t), 30.0);
  }
}

TEST(Actor, LatLonNeedsAnOriginAndConverts) {
  const Json doc =
      Json::parse(R"({"name": "c", "position": {"lat_deg": 46.8427, "lon_deg": -91.99445, "height_m": 160}})");
  const JsonField f(doc, "shots.json", "actors[0]");
  EXPECT_THROW(ParseActor(f, nullptr), InputError);
  const EnuFrame frame(Geodetic{46.8426, -91.99445, 150});
  const Actor c = ParseActor(f, &frame);
  EXPECT_NEAR(c.PositionAt(0).x(), 0.0, 1e-6);
  EXPECT_NEAR(c.PositionAt(0).y(), 11.12, 0.02);
  EXPECT_NEAR(c.PositionAt(0).z(), 10.0, 0.01);
}

TEST(Actor, BadActorsNameTheField) {
  const Json doc = Json::parse(R"({"name": "d", "position_enu_m": [1]})");
  try {
    ParseActor(JsonField(doc, "shots.json", "actors[3]"), nullptr);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "shots.json: actors[3].position_enu_m: expected [east_m, north_m, up_m], or [east_m, north_m] on the "
                 "ground");
  }
  // [east, north] stands on the ground, which needs the scene's mesh.
  const Json on_ground = Json::parse(R"({"name": "d", "position_enu_m": [1, 2]})");
  try {
    ParseActor(JsonField(on_ground, "shots.json", "actors[3]"), nullptr);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(
        e.what(),
        "shots.json: actors[3].position_enu_m: a height above the ground needs the scene's mesh (`scene_mesh`)");
  }
  const Json both = Json::parse(R"({"name": "d", "position_enu_m": [1, 2, 3], "keyframes": []})");
  EXPECT_THROW(ParseActor(JsonField(both, "shots.json", "actors[0]"), nullptr), InputError);
}

}  // namespace
}  // namespace cinepath::shots

namespace cinepath::shots {
namespace {

TEST(Actor, AmslHeightsGoThroughEgm96) {
  // At the origin's own lat/lon, AMSL H puts the actor at h = H + N above the ellipsoid.
  const Geodetic origin{47.3977, 8.5456, 500};
  const EnuFrame frame(origin);
  const Json doc = Json::parse(R"({"name": "e", "position": {"lat_deg": 47.3977, "lon_deg": 8.5456, "amsl_m": 460}})");
  const Actor e = ParseActor(JsonField(doc, "shots.json", "actors[0]"), &frame);
  EXPECT_NEAR(e.PositionAt(0).z(), 460 + 47.34 - 500, 0.05);  // N(47.3977, 8.5456) ~ 47.34 m
  const Json both =
      Json::parse(R"({"name": "e", "position": {"lat_deg": 47.3977, "lon_deg": 8.5456, "amsl_m": 1, "height_m": 2}})");
  EXPECT_THROW(ParseActor(JsonField(both, "shots.json", "actors[0]"), &frame), InputError);
}

}  // namespace
}  // namespace cinepath::shots
