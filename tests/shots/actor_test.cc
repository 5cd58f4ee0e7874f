#include "shots/actor.h"

#include <gtest/gtest.h>

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
