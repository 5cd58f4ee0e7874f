#include "shots/team_planner.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/angles.h"
#include "core/error.h"
#include "core/plan_file.h"
#include "core/team_checks.h"

namespace cinepath::shots {
namespace {

using Eigen::Vector3d;

constexpr const char* kCamera =
    R"({"filmback": "super35", "width_px": 3840, "height_px": 2160, "min_focal_length_mm": 12,
        "max_focal_length_mm": 1200})";

// Two drones ("a", "b") around one actor at the origin; `shots` and `edit` are JSON text.
Json TeamDoc(const std::string& shots, const std::string& edit = "", const std::string& actors = "") {
  const std::string actor_list =
      actors.empty() ? R"([{"name": "hero", "height_m": 1.8, "position_enu_m": [0, 0, 0]}])" : actors;
  return Json::parse(std::string(R"({"schema": "cinepath.shots/1", "frame_rate_hz": 30, "camera": )") + kCamera +
                     R"(, "drone": "px4-multirotor", "drones": [{"name": "a"}, {"name": "b"}], "actors": )" +
                     actor_list + R"(, "shots": )" + shots + (edit.empty() ? "" : R"(, "edit": )" + edit) + "}");
}

TeamPlan PlanDoc(const Json& doc) { return PlanTeam(ParseShotList(doc, "shots.json")); }

// Two ORBITs of the same subject at the same radius, half a turn apart.
std::string OrbitPair(double focal_length_mm) {
  const std::string lens = R"(, "lens": {"focal_length_mm": )" + std::to_string(focal_length_mm) + "}";
  return R"([{"name": "oa", "drone": "a", "type": "ORBIT", "subject": "hero", "duration_s": 20, "radius_m": 20,
              "height_m": 5, "turns": 1, "direction": "cw", "start_bearing_deg": 0, "easing": "linear")" +
         lens + R"(},
             {"name": "ob", "drone": "b", "type": "ORBIT", "subject": "hero", "duration_s": 20, "radius_m": 20,
              "height_m": 5, "turns": 1, "direction": "cw", "start_bearing_deg": 180, "easing": "linear")" +
         lens + "}]";
}

std::vector<TeamConflict> ConflictsOf(const TeamPlan& plan, const std::string& limit) {
  std::vector<TeamConflict> out;
  for (const auto& c : plan.team.conflicts) {
    if (c.limit == limit) out.push_back(c);
  }
  return out;
}

TEST(PlanTeam, OrbitsHalfATurnApartMatchTheClosedForm) {
  const TeamPlan plan = PlanDoc(TeamDoc(OrbitPair(85)));
  ASSERT_EQ(plan.flights.size(), 2u);
  ASSERT_EQ(plan.flights[0].plan.samples.size(), 601u);
  ASSERT_EQ(plan.flights[1].plan.samples.size(), 601u);
  for (size_t k = 0; k < 601; ++k) {
    const double t = static_cast<double>(k) / 30.0;
    for (int d = 0; d < 2; ++d) {
      const double bearing = RadFromDeg(180.0 * d + 360.0 * t / 20.0);  // clockwise: the compass bearing grows
      const Vector3d expected(20 * std::sin(bearing), 20 * std::cos(bearing), 5);
      EXPECT_NEAR((plan.flights[d].plan.samples[k].position_enu_m - expected).norm(), 0.0, 1e-9) << d << " " << k;
      EXPECT_NEAR(plan.flights[d].plan.samples[k].time_s, t, 1e-12);
    }
  }
  // 40 m apart at every sample: no separation breach; at 85 mm the other drone (11.6 deg above the
  // axis) is outside the 4.7 deg half-height of the frame.
  EXPECT_TRUE(plan.team.clear());
  EXPECT_DOUBLE_EQ(plan.team.min_separation_m, 5.0);
}

TEST(PlanTeam, AWideFrameSeesTheOtherDroneAndNamesTheTimes) {
  const TeamPlan plan = PlanDoc(TeamDoc(OrbitPair(24)));
  const auto seen = ConflictsOf(plan, "in_shot");
  ASSERT_EQ(seen.size(), 2u);  // each drone in the other's shot, the whole flight
  EXPECT_EQ(seen[0].drone, "a");
  EXPECT_EQ(seen[0].other, "b");
  EXPECT_EQ(seen[1].drone, "b");
  EXPECT_EQ(seen[1].other, "a");
  for (const auto& c : seen) {
    EXPECT_DOUBLE_EQ(c.start_time_s, 0.0);
    EXPECT_NEAR(c.end_time_s, 20.0, 1e-9);
    // A 0.8 m sphere 40 m away through 24 mm on a 24.89 mm-wide 3840 px sensor: 2 f r / d in pixels.
    const double focal_px = 24.0 / 24.89 * 3840;
    EXPECT_NEAR(c.worst_value, 2 * focal_px * std::tan(std::asin(0.4 / 40.0)), 1e-6);
    EXPECT_EQ(c.unit, "px");
  }
  EXPECT_TRUE(ConflictsOf(plan, "separation").empty());
}

TEST(PlanTeam, AnEditChecksOnlyTheLiveCamera) {
  const TeamPlan plan = PlanDoc(TeamDoc(OrbitPair(24), R"([{"at_s": 0, "drone": "a"}, {"at_s": 8, "drone": "b"}])"));
  const auto seen = ConflictsOf(plan, "in_shot");
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].drone, "a");
  EXPECT_DOUBLE_EQ(seen[0].start_time_s, 0.0);
  EXPECT_NEAR(seen[0].end_time_s, 8.0 - 1.0 / 30.0, 1e-9);
  EXPECT_EQ(seen[1].drone, "b");
  EXPECT_NEAR(seen[1].start_time_s, 8.0, 1e-9);
  EXPECT_NEAR(seen[1].end_time_s, 20.0, 1e-9);
}

// Two walkers crossing at the origin at t = 12 s, each chased 10 m behind at 5 m: the drones meet there.
constexpr const char* kCrossingActors = R"([
  {"name": "east", "height_m": 1.8, "interpolation": "linear", "keyframes": [
    {"time_s": 0, "position_enu_m": [-50, 0, 0]}, {"time_s": 20, "position_enu_m": [50, 0, 0]}]},
  {"name": "north", "height_m": 1.8, "interpolation": "linear", "keyframes": [
    {"time_s": 0, "position_enu_m": [0, -50, 0]}, {"time_s": 20, "position_enu_m": [0, 50, 0]}]}])";
constexpr const char* kCrossingShots = R"([
  {"name": "ca", "drone": "a", "type": "CHASE", "subject": "east", "duration_s": 20, "distance_m": 10, "height_m": 5,
   "lens": {"focal_length_mm": 200}},
  {"name": "cb", "drone": "b", "type": "CHASE", "subject": "north", "duration_s": 20, "distance_m": 10,
   "height_m": 5, "lens": {"focal_length_mm": 200}}])";

TEST(PlanTeam, CrossingChasesReportTheSeparationBreachWithItsTimes) {
  const TeamPlan plan = PlanDoc(TeamDoc(kCrossingShots, "", kCrossingActors));
  const auto breaches = ConflictsOf(plan, "separation");
  ASSERT_EQ(breaches.size(), 1u);
  // |a - b| = sqrt(2) |5 t - 60| < 5 m  <=>  |t - 12| < 1 / sqrt(2): samples 11.3 .. 12.7 s at 30 fps.
  EXPECT_EQ(breaches[0].drone, "a");
  EXPECT_EQ(breaches[0].other, "b");
  EXPECT_NEAR(breaches[0].start_time_s, 339.0 / 30.0, 1e-9);
  EXPECT_NEAR(breaches[0].end_time_s, 381.0 / 30.0, 1e-9);
  EXPECT_NEAR(breaches[0].worst_value, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(breaches[0].limit_value, 5.0);
}

TEST(PlanTeam, MatchedFocusSharesTheOutgoingSubjectAtTheCut) {
  // a frames hero; b frames a second actor 30 m away, then the cut to b at 10 s asks for hero's focus.
  const std::string actors = R"([{"name": "hero", "height_m": 1.8, "position_enu_m": [0, 0, 0]},
                                 {"name": "far", "height_m": 1.8, "position_enu_m": [0, 30, 0]}])";
  const std::string shots = R"([
    {"name": "oa", "drone": "a", "type": "ORBIT", "subject": "hero", "duration_s": 20, "radius_m": 20, "height_m": 5,
     "turns": 0.1, "start_bearing_deg": 180},
    {"name": "ob", "drone": "b", "type": "ORBIT", "subject": "far", "duration_s": 20, "radius_m": 15, "height_m": 5,
     "turns": 0.1, "start_bearing_deg": 90}])";
  const TeamPlan matched = PlanDoc(
      TeamDoc(shots, R"([{"at_s": 0, "drone": "a"}, {"at_s": 10, "drone": "b", "match_focus": true}])", actors));
  ASSERT_EQ(matched.team.focus_matches.size(), 1u);
  const FocusMatch& m = matched.team.focus_matches[0];
  EXPECT_EQ(m.from_drone, "a");
  EXPECT_EQ(m.to_drone, "b");
  EXPECT_EQ(m.subject, "hero");
  EXPECT_LT(m.from_focus_error_dioptres, 1e-9);
  EXPECT_LT(m.to_focus_error_dioptres, 1e-9);

  // Without match_focus, b stays on its own subject: a large error on hero.
  const TeamPlan plain = PlanDoc(TeamDoc(shots, R"([{"at_s": 0, "drone": "a"}, {"at_s": 10, "drone": "b"}])", actors));
  EXPECT_TRUE(plain.team.focus_matches.empty());
  const auto& b_plain = plain.flights[1].plan.samples[300];
  const auto& b_matched = matched.flights[1].plan.samples[300];
  EXPECT_GT(std::fabs(1 / b_plain.focus_distance_m - 1 / b_matched.focus_distance_m), 0.005);
  // Before the ramp (b not live yet) the two plans agree.
  EXPECT_DOUBLE_EQ(plain.flights[1].plan.samples[200].focus_distance_m,
                   matched.flights[1].plan.samples[200].focus_distance_m);
}

TEST(PlanTeam, ShotsOfOneDroneRunBackToBackOnTheSharedClock) {
  const std::string shots = R"([
    {"name": "a1", "drone": "a", "type": "ORBIT", "subject": "hero", "duration_s": 4, "radius_m": 20, "height_m": 5,
     "turns": 0.1},
    {"name": "b1", "drone": "b", "type": "ORBIT", "subject": "hero", "duration_s": 6, "radius_m": 20, "height_m": 5,
     "turns": 0.1, "start_bearing_deg": 180},
    {"name": "a2", "drone": "a", "type": "ORBIT", "subject": "hero", "duration_s": 3, "radius_m": 25, "height_m": 5,
     "turns": 0.1}])";
  const TeamPlan plan = PlanDoc(TeamDoc(shots));
  ASSERT_EQ(plan.flights[0].plan.shots.size(), 2u);
  EXPECT_DOUBLE_EQ(plan.flights[0].plan.shots[1].start_time_s, 4.0);
  EXPECT_DOUBLE_EQ(plan.flights[0].plan.shots[1].end_time_s, 7.0);
  EXPECT_EQ(plan.flights[0].plan.samples.size(), 7u * 30u + 1u);
  EXPECT_EQ(plan.flights[1].plan.samples.size(), 6u * 30u + 1u);
  EXPECT_EQ(plan.SampleCount(), 211u);
}

void ExpectInputError(const Json& doc, const std::string& message) {
  try {
    PlanDoc(doc);
    FAIL() << "expected InputError: " << message;
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(PlanTeam, BadInputNamesTheJsonPath) {
  Json doc = TeamDoc(OrbitPair(50));
  doc["shots"][1]["drone"] = "c";
  ExpectInputError(doc, "shots.json: shots[1].drone: no drone is named \"c\" (see \"drones\")");

  doc = TeamDoc(OrbitPair(50));
  doc["drones"][1]["name"] = "a";
  ExpectInputError(doc, "shots.json: drones[1].name: duplicate drone name \"a\"");

  doc = TeamDoc(OrbitPair(50));
  doc["shots"][0].erase("drone");
  ExpectInputError(doc,
                   "shots.json: shots[0]: missing \"drone\": with \"drones\", every shot names the drone that "
                   "flies it");

  doc = TeamDoc(OrbitPair(50), R"([{"at_s": 0, "drone": "a"}, {"at_s": 25, "drone": "b"}])");
  ExpectInputError(doc, "shots.json: edit[1].at_s: cuts after the plan ends (20 s)");

  doc = TeamDoc(OrbitPair(50), R"([{"at_s": 5, "drone": "a"}, {"at_s": 2, "drone": "b"}])");
  ExpectInputError(doc, "shots.json: edit[1].at_s: cuts must be in increasing time");

  doc = TeamDoc(OrbitPair(50));
  doc["drones"][0]["name"] = "../x";
  EXPECT_THROW(PlanDoc(doc), InputError);

  doc = TeamDoc(OrbitPair(50));
  doc.erase("drones");
  ExpectInputError(doc, "shots.json: shots[0].drone: names a drone, but the shot list has no \"drones\"");
}

TEST(TeamPlanFile, VersionTwoRoundTripsAndVersionOneStaysByteIdentical) {
  const TeamPlan plan = PlanDoc(TeamDoc(OrbitPair(24), R"([{"at_s": 0, "drone": "a"}, {"at_s": 8, "drone": "b"}])"));
  const std::string text = TeamPlanToText(plan);
  const TeamPlan back = TeamPlanFromJson(Json::parse(text), "plan.json");
  EXPECT_EQ(TeamPlanToText(back), text);
  ASSERT_EQ(back.flights.size(), 2u);
  EXPECT_EQ(back.edit.size(), 2u);
  EXPECT_EQ(back.team.conflicts.size(), plan.team.conflicts.size());
  EXPECT_DOUBLE_EQ(back.flights[1].plan.drone.body_radius_m, 0.4);

  // A one-drone plan reads as a one-flight team and writes back as the same version 1 bytes.
  const std::string v1 = PlanToText(plan.flights[0].plan);
  const TeamPlan single = TeamPlanFromJson(Json::parse(v1), "plan.json");
  EXPECT_TRUE(single.single);
  EXPECT_EQ(TeamPlanToText(single), v1);
  EXPECT_EQ(v1.find("body_radius_m"), std::string::npos);

  // A step that reads one flight names the version it got.
  try {
    PlanFromJson(Json::parse(text), "plan.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("several drones"), std::string::npos) << e.what();
  }
}

TEST(TeamChecks, ProjectedBodyDiameterOnAndOffTheFrame) {
  CameraSpec camera;  // Super 35, 3840 x 2160
  const Eigen::Quaterniond north = Eigen::Quaterniond(Eigen::AngleAxisd(-M_PI / 2, Vector3d::UnitX()));
  // Camera looking north (z forward = +n): a body 100 m ahead on the axis.
  const Vector3d forward = north * Vector3d::UnitZ();
  ASSERT_NEAR((forward - Vector3d(0, 1, 0)).norm(), 0.0, 1e-12);
  const double f_px = 50.0 / camera.sensor_width_mm * camera.width_px;
  EXPECT_NEAR(ProjectedBodyDiameterPx(camera, Vector3d::Zero(), north, 50, Vector3d(0, 100, 0), 0.5),
              2 * f_px * std::tan(std::asin(0.005)), 1e-9);
  // Behind the camera, or beside the frame: not seen.
  EXPECT_EQ(ProjectedBodyDiameterPx(camera, Vector3d::Zero(), north, 50, Vector3d(0, -100, 0), 0.5), 0.0);
  EXPECT_EQ(ProjectedBodyDiameterPx(camera, Vector3d::Zero(), north, 50, Vector3d(100, 100, 0), 0.5), 0.0);
  // Just outside the frame's edge, its disc still overlaps the image.
  const double edge_e = 100 * (camera.width_px / 2.0) / f_px;
  EXPECT_GT(ProjectedBodyDiameterPx(camera, Vector3d::Zero(), north, 50, Vector3d(edge_e + 0.3, 100, 0), 0.5), 0);
  EXPECT_EQ(ProjectedBodyDiameterPx(camera, Vector3d::Zero(), north, 50, Vector3d(edge_e + 0.7, 100, 0), 0.5), 0.0);
}

}  // namespace
}  // namespace cinepath::shots
