#include "shots/shot_list.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/plan_file.h"
#include "shots/planner.h"

#include <cmath>
#include <functional>

namespace cinepath::shots {
namespace {

const char* kBase = R"({
  "schema": "cinepath.shots/1",
  "camera": {"filmback": "super35", "min_focal_length_mm": 24, "max_focal_length_mm": 70},
  "actors": [{"name": "hero", "position_enu_m": [0, 0, 0]}],
  "shots": [{"type": "ORBIT", "subject": "hero", "duration_s": 5, "radius_m": 10, "height_m": 5, "turns": 1}]
})";

// Applies a JSON merge patch to the base document and expects the exact message.
std::string ErrorFor(const std::string& patch) {
  Json doc = Json::parse(kBase);
  doc.merge_patch(Json::parse(patch));
  try {
    ParseShotList(doc, "shots.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ShotList, ParsesTheBaseDocumentWithDefaults) {
  const ShotList list = ParseShotList(Json::parse(kBase), "shots.json");
  EXPECT_EQ(list.frame_rate_hz, 30);
  EXPECT_EQ(list.drone.name, "px4-multirotor");
  EXPECT_NEAR(list.camera.sensor_width_mm, 24.89, 1e-9);
  ASSERT_EQ(list.shots.size(), 1u);
  EXPECT_EQ(list.shots[0].name, "shot1");
  EXPECT_EQ(list.shots[0].total_angle_deg, -360.0);  // ccw by default
  EXPECT_FALSE(list.origin.has_value());
}

TEST(ShotList, BadSpecsNameTheJsonPath) {
  EXPECT_EQ(ErrorFor(
                R"({"shots": [{"type": "ORBIT", "subject": "hero", "duration_s": 5, "radius_m": 0, "height_m": 5,
            "turns": 1}]})"),
            "shots.json: shots[0].radius_m: must be > 0");
  EXPECT_EQ(ErrorFor(
                R"({"shots": [{"type": "ORBIT", "subject": "hero", "duration_s": 5, "raduis_m": 3, "height_m": 5,
            "turns": 1}]})"),
            "shots.json: shots[0].raduis_m: unknown key for a ORBIT shot");
  EXPECT_EQ(ErrorFor(R"({"shots": [{"type": "SPIRAL", "duration_s": 5}]})")
                .rfind("shots.json: shots[0].type: unknown shot type \"SPIRAL\" (CHASE, ORBIT", 0),
            0u);
  EXPECT_EQ(ErrorFor(
                R"({"shots": [{"type": "ORBIT", "subject": "villain", "duration_s": 5, "radius_m": 3, "height_m": 5,
            "turns": 1}]})"),
            "shots.json: shots[0].subject: no actor named \"villain\"");
  EXPECT_EQ(ErrorFor(
                R"({"shots": [{"type": "ORBIT", "subject": "hero", "duration_s": -1, "radius_m": 3, "height_m": 5,
            "turns": 1}]})"),
            "shots.json: shots[0].duration_s: must be >= 0");
  EXPECT_EQ(
      ErrorFor(R"({"shots": [{"type": "ORBIT", "subject": "hero", "duration_s": 5, "radius_m": 3, "height_m": 5}]})"),
      "shots.json: shots[0]: give exactly one of \"turns\" or \"angular_speed_deg_s\"");
  EXPECT_EQ(ErrorFor(R"({"shots": [{"type": "ORBIT", "duration_s": 5, "radius_m": 3, "height_m": 5, "turns": 1}]})"),
            "shots.json: shots[0]: a ORBIT shot needs a \"subject\"");
  EXPECT_EQ(ErrorFor(
                R"({"shots": [{"type": "ORBIT", "subject": "hero", "duration_s": 5, "radius_m": 3, "height_m": 5,
            "turns": 1, "easing": "bouncy"}]})")
                .rfind("shots.json: shots[0].easing: unknown easing \"bouncy\" (linear", 0),
            0u);
  EXPECT_EQ(ErrorFor(R"({"schema": "cinepath.shots/2"})"),
            "shots.json: schema: unsupported shot-list version \"cinepath.shots/2\" (expected \"cinepath.shots/1\")");
  EXPECT_EQ(ErrorFor(R"({"camera": {"filmback": "imax"}})")
                .rfind("shots.json: camera.filmback: unknown filmback \"imax\" (", 0),
            0u);
  EXPECT_EQ(ErrorFor(R"({"drone": "mavic9"})"),
            "shots.json: drone: unknown drone profile \"mavic9\" (known: px4-multirotor, ardupilot-copter, "
            "dji-m30, dji-mini4pro)");
  EXPECT_EQ(ErrorFor(R"({"actors": [{"name": "hero", "position": {"lat_deg": 1, "lon_deg": 2, "height_m": 3}}]})"),
            "shots.json: actors[0].position: a lat/lon position needs a WGS84 origin (shots.json \"origin\" or "
            "`scene_origin`)");
  EXPECT_EQ(ErrorFor(R"({"origin": {"lat_deg": 91, "lon_deg": 0, "height_m": 0}})"),
            "shots.json: origin.lat_deg: must be in [-90, 90]");
  EXPECT_EQ(ErrorFor(
                R"({"shots": [{"type": "DOLLY-ZOOM", "subject": "hero", "duration_s": 5, "distance_m": 3,
            "distance_end_m": 9}]})"),
            "shots.json: shots[0]: a DOLLY-ZOOM shot needs \"lens\" with frame_height_fraction or focal_length_mm");
  EXPECT_EQ(
      ErrorFor(
          R"({"shots": [{"type": "ORBIT", "subject": "hero", "duration_s": 5, "radius_m": 3, "height_m": 5, "turns": 1,
                         "lens": {"f_number": 1.2}}]})"),
      "shots.json: shots[0].lens.f_number: must be in [2.8, 16] (the camera's range)");
  EXPECT_EQ(
      ErrorFor(R"({"shots": [{"type": "KEYFRAMES", "keys": [{"time_s": 0, "position_enu_m": [0, 0, 1]}]}]})"),
      "shots.json: shots[0].keys[0]: needs an orientation (look_at or heading/pitch/roll): the shot has no subject");
  EXPECT_EQ(
      ErrorFor(
          R"({"shots": [{"type": "KEYFRAMES", "subject": "hero", "keys": [{"time_s": 2, "position_enu_m": [0, 0, 1]},
                         {"time_s": 1, "position_enu_m": [0, 0, 1]}]}]})"),
      "shots.json: shots[0].keys[1].time_s: key times must increase (by 1 ms or more)");
  EXPECT_EQ(
      ErrorFor(
          R"({"shots": [{"type": "DRONIE", "subject": "hero", "duration_s": 5, "distance_m": 30, "distance_end_m": 10,
                         "height_m": 2, "height_end_m": 20}]})"),
      "shots.json: shots[0].distance_end_m: a DRONIE flies away: must be > distance_m");
}

TEST(ShotList, OriginFromTheSceneAndLatLonActors) {
  Json doc = Json::parse(kBase);
  doc["actors"][0] =
      Json::parse(R"({"name": "hero", "position": {"lat_deg": 46.8427, "lon_deg": -91.9944, "height_m": 160}})");
  const Geodetic origin{46.8426, -91.9945, 150};
  const ShotList list = ParseShotList(doc, "shots.json", origin);
  ASSERT_TRUE(list.origin.has_value());
  const Eigen::Vector3d p = list.actors[0].PositionAt(0);
  EXPECT_NEAR(p.y(), 11.12, 0.05);  // 1e-4 deg of latitude ~ 11.1 m
  EXPECT_NEAR(p.x(), 7.62, 0.05);   // 1e-4 deg of longitude at 46.84 deg ~ 7.6 m
  EXPECT_NEAR(p.z(), 10.0, 0.01);
  // A conflicting origin in shots.json is refused.
  doc["origin"] = Json::parse(R"({"lat_deg": 10, "lon_deg": 10, "height_m": 0})");
  EXPECT_THROW(ParseShotList(doc, "shots.json", origin), InputError);
}

TEST(ShotListDrone, NamedProfileAndOverrides) {
  EXPECT_EQ(ParseShotList(Json::parse(kBase), "shots.json").drone.name, "px4-multirotor");
  // Overrides on top of a profile.
  Json doc = Json::parse(kBase);
  doc["drone"] = Json::parse(R"({"profile": "dji-m30", "max_horizontal_speed_m_s": 10})");
  const ShotList list = ParseShotList(doc, "shots.json");
  EXPECT_EQ(list.drone.name, "dji-m30");
  EXPECT_EQ(list.drone.max_horizontal_speed_m_s, 10);
  EXPECT_EQ(list.drone.max_gimbal_pitch_deg, 45);  // the M30 gimbal, as the profile has it
}

}  // namespace
}  // namespace cinepath::shots

namespace cinepath::shots {
namespace {

// Every number of every example replaced by hostile values: the planner either plans or throws
// InputError (exit 2) — never another exception, a crash or a non-finite sample.
void Visit(Json& node, const std::function<void(Json&)>& f) {
  f(node);
  if (node.is_object()) {
    for (auto& [k, v] : node.items()) Visit(v, f);
  } else if (node.is_array()) {
    for (auto& v : node) Visit(v, f);
  }
}

TEST(ShotList, HostileNumbersAreCleanErrors) {
  for (const char* example : {"orbit_shots.json", "flyby_chase_track_shots.json", "keyframes_shots.json",
                              "crane_dronie_shots.json", "topdown_lockedoff_shots.json", "dolly_zoom_shots.json"}) {
    SCOPED_TRACE(example);
    const Json original = ParseJsonFile(std::string(CINEPATH_SOURCE_DIR) + "/examples/" + example);
    size_t numbers = 0;
    {
      Json copy = original;
      Visit(copy, [&](Json& n) { numbers += n.is_number() ? 1 : 0; });
    }
    ASSERT_GT(numbers, 20u);
    PlanOptions options;
    options.max_samples = 200000;
    size_t planned = 0, refused = 0;
    for (const double hostile : {0.0, -1.0, 1e308, -1e308, 1e-300, 1e-320, 5e-324, -1e-9, 1e7}) {
      for (size_t target = 0; target < numbers; ++target) {
        Json doc = original;
        size_t i = 0;
        Visit(doc, [&](Json& n) {
          if (n.is_number() && i++ == target) n = hostile;
        });
        try {
          const Trajectory plan = PlanShots(ParseShotList(doc, "shots.json"), options);
          for (const auto& s : plan.samples) {
            ASSERT_TRUE(s.position_enu_m.allFinite() && s.world_from_camera.coeffs().allFinite() &&
                        std::isfinite(s.focal_length_mm) && std::isfinite(s.drone_heading_deg))
                << "number #" << target << " = " << hostile;
          }
          EXPECT_FALSE(PlanToText(plan).empty());  // no NaN reaches the writer (InternalError)
          ++planned;
        } catch (const InputError&) {
          ++refused;
        } catch (const std::exception& e) {
          ADD_FAILURE() << "number #" << target << " = " << hostile << ": " << e.what();
        }
      }
    }
    EXPECT_GT(planned, 0u);
    EXPECT_GT(refused, 0u);
  }
}

}  // namespace
}  // namespace cinepath::shots
