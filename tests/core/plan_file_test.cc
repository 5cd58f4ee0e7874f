#include "core/plan_file.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/drone_profiles.h"
#include "core/error.h"
#include "tests/support/input_error.h"

namespace cinepath {
namespace {

Trajectory SmallPlan() {
  Trajectory plan;
  plan.origin = Geodetic{46.84265, -91.99445, 153.0};
  plan.frame_rate_hz = 2;
  plan.shots.push_back({"a", "ORBIT", 0.0, 1.0, "hero", "continuous"});
  for (int i = 0; i < 3; ++i) {
    TrajectorySample s;
    s.time_s = 0.5 * i;
    s.position_enu_m = Eigen::Vector3d(1.0 + i, -2.0, 10.0);
    s.geodetic = Geodetic{46.8427, -91.9944, 163.0 + i};
    s.world_from_camera = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(1, 2, 3).normalized()));
    s.drone_heading_deg = 10.0 * i;
    s.gimbal_pitch_deg = -30;
    s.focal_length_mm = 35;
    s.focus_distance_m = i == 2 ? std::numeric_limits<double>::infinity() : 12.5;
    s.f_number = 4;
    s.shot = "a";
    s.subjects_in_frame = {"hero"};
    plan.samples.push_back(s);
  }
  plan.subjects.push_back({"hero", 1.8, {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}});
  Keyframe k;
  k.shot = "a";
  k.focus_distance_m = std::numeric_limits<double>::infinity();
  plan.keyframes.push_back(k);
  plan.feasibility.violations.push_back({"horizontal_speed", "a", 0.5, 1.0, 13.5, 12, "m/s"});
  return plan;
}

TEST(PlanFile, VersionedAndInfinityIsNull) {
  const Json j = PlanToJson(SmallPlan());
  EXPECT_EQ(j["schema"], "cinepath.plan/1");
  EXPECT_TRUE(j["samples"][2]["focus_distance_m"].is_null());
  EXPECT_EQ(j["samples"][0]["focus_distance_m"], 12.5);
  EXPECT_TRUE(j["keyframes"][0]["focus_distance_m"].is_null());
  EXPECT_EQ(j["feasibility"]["feasible"], false);
  EXPECT_EQ(j["samples"][0]["lat_deg"], 46.8427);
  EXPECT_EQ(j["samples"][0]["world_from_camera"].size(), 4u);
}

TEST(PlanFile, RoundTripsToTheSameBytes) {
  const std::string text = PlanToText(SmallPlan());
  const Trajectory back = PlanFromJson(Json::parse(text), "plan.json");
  EXPECT_TRUE(std::isinf(back.samples[2].focus_distance_m));
  EXPECT_TRUE(std::isinf(back.keyframes[0].focus_distance_m));
  EXPECT_EQ(back.samples[1].subjects_in_frame, std::vector<std::string>{"hero"});
  ASSERT_TRUE(back.origin.has_value());
  EXPECT_EQ(back.origin->lat_deg, 46.84265);
  EXPECT_EQ(back.feasibility.violations.size(), 1u);
  EXPECT_EQ(back.shots[0].subject, "hero");
  EXPECT_TRUE(PlanToText(back) == text);
}

TEST(PlanFile, RefusesOtherVersionsAndNamesTheField) {
  Json j = PlanToJson(SmallPlan());
  j["schema"] = "cinepath.plan/9";
  try {
    PlanFromJson(j, "plan.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("plan.json: schema: unsupported plan version \"cinepath.plan/9\"", 0), 0u);
  }
  // Version 2 (several drones) is known, but a one-flight reader says what it got.
  j["schema"] = "cinepath.plan/2";
  try {
    PlanFromJson(j, "plan.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("plan.json: schema: this plan holds several drones", 0), 0u) << e.what();
  }
  j = PlanToJson(SmallPlan());
  j["samples"][1]["time_s"] = 0.0;
  EXPECT_THROW(PlanFromJson(j, "plan.json"), InputError);
  j = PlanToJson(SmallPlan());
  j["samples"][0]["world_from_camera"] = Json::array({0, 0, 0, 0});
  try {
    PlanFromJson(j, "plan.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("plan.json: samples[0].world_from_camera: not a unit quaternion", 0), 0u);
  }
}

TEST(PlanFile, CsvHasOneRowPerSample) {
  const std::string csv = PlanSamplesToCsv(SmallPlan());
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  EXPECT_EQ(csv.rfind("time_s,shot,east_m,north_m,up_m,lat_deg,lon_deg,height_m,qw,qx,qy,qz,", 0), 0u);
  EXPECT_NE(csv.find(",inf,4,"), std::string::npos);
  EXPECT_NE(csv.find("\n0,a,1,-2,10,46.8427,-91.9944,163,"), std::string::npos);
}

// Every number is checked where it is read, against the domains of docs/plan-format.md, and the message
// names the file and the JSON path. The cases the mutation runs found: a height of -1e308 (finite, so
// accepted before, then an overflow in export's JSON writer, exit 1).
std::string ReadError(const Json& j) {
  return testing::InputErrorMessage([&] { PlanFromJson(j, "plan.json"); });
}

TEST(PlanFileDomains, PositionsAndHeightsWithin1e7MetresOfTheOrigin) {
  Json j = PlanToJson(SmallPlan());
  j["samples"][1]["height_m"] = -1e308;
  EXPECT_EQ(ReadError(j), "plan.json: samples[1].height_m: must lie within 1e7 m of the origin, got -1e+308");
  j = PlanToJson(SmallPlan());
  j["samples"][2]["position_enu_m"][2] = 2e7;
  EXPECT_EQ(ReadError(j), "plan.json: samples[2].position_enu_m[2]: must lie within 1e7 m of the origin, got 2e+07");
  j = PlanToJson(SmallPlan());
  j["subjects"][0]["positions_enu_m"][0][0] = -1e300;
  EXPECT_EQ(ReadError(j).rfind("plan.json: subjects[0].positions_enu_m[0][0]: must lie within 1e7 m", 0), 0u);
  j = PlanToJson(SmallPlan());
  j["keyframes"][0]["position_enu_m"][1] = 1e7;  // the bound itself is inside
  EXPECT_NO_THROW(PlanFromJson(j, "plan.json"));
  j["samples"][0]["lat_deg"] = 91.0;
  EXPECT_EQ(ReadError(j), "plan.json: samples[0].lat_deg: must be in [-90, 90]");
}

TEST(PlanFileDomains, TimesFiniteInRangeAndIncreasing) {
  Json j = PlanToJson(SmallPlan());
  j["samples"][1]["time_s"] = 1e-9;  // after 0, but closer than a microsecond
  EXPECT_EQ(ReadError(j), "plan.json: samples[1].time_s: times must increase (by at least 1e-6 s)");
  j = PlanToJson(SmallPlan());
  j["samples"][0]["time_s"] = -1.0;
  EXPECT_EQ(ReadError(j), "plan.json: samples[0].time_s: must be in [0, 1e+06]");
  j = PlanToJson(SmallPlan());
  j["shots"][0]["end_time_s"] = 1e300;
  EXPECT_EQ(ReadError(j), "plan.json: shots[0].end_time_s: must be in [0, 1e+06]");
  j = PlanToJson(SmallPlan());
  j["samples"] = Json::array();
  EXPECT_EQ(ReadError(j), "plan.json: samples: must hold at least one sample");
}

TEST(PlanFileDomains, QuaternionsNormalizedWhenCloseRefusedWhenFar) {
  Json j = PlanToJson(SmallPlan());
  j["samples"][0]["world_from_camera"] = Json::array({1.0005, 0, 0, 0});
  const Trajectory read = PlanFromJson(j, "plan.json");
  EXPECT_NEAR(read.samples[0].world_from_camera.norm(), 1.0, 1e-15);
  j["samples"][0]["world_from_camera"] = Json::array({1.01, 0, 0, 0});
  EXPECT_EQ(ReadError(j),
            "plan.json: samples[0].world_from_camera: not a unit quaternion (norm 1.01; must be within 0.001 of 1)");
  j["samples"][0]["world_from_camera"] = Json::array({0.7, 0, 0, 0.7});
  EXPECT_EQ(ReadError(j).rfind("plan.json: samples[0].world_from_camera: not a unit quaternion", 0), 0u);
}

TEST(PlanFileDomains, LensInTheRangesOfTheOpticsPage) {
  Json j = PlanToJson(SmallPlan());
  j["samples"][0]["focus_distance_m"] = 0.02;  // inside the 35 mm focal length: no real image
  EXPECT_EQ(ReadError(j),
            "plan.json: samples[0].focus_distance_m: 0.02 m is inside the focal length 35 mm (no real image)");
  j = PlanToJson(SmallPlan());
  j["samples"][0]["focus_distance_m"] = -3;
  EXPECT_EQ(ReadError(j),
            "plan.json: samples[0].focus_distance_m: must be at least 0.001 m (null for infinity), got -3");
  // A rack to infinity in dioptres passes through huge distances: read as they are up to 1e15 m, as
  // infinity beyond.
  j = PlanToJson(SmallPlan());
  j["samples"][0]["focus_distance_m"] = 1.6e8;
  j["samples"][1]["focus_distance_m"] = 1e300;
  const Trajectory far = PlanFromJson(j, "plan.json");
  EXPECT_EQ(far.samples[0].focus_distance_m, 1.6e8);
  EXPECT_TRUE(std::isinf(far.samples[1].focus_distance_m));
  j = PlanToJson(SmallPlan());
  j["samples"][1]["f_number"] = 0.05;
  EXPECT_EQ(ReadError(j), "plan.json: samples[1].f_number: must be in [0.1, 1000]");
  j = PlanToJson(SmallPlan());
  j["samples"][1]["shutter_s"] = 120;
  EXPECT_EQ(ReadError(j), "plan.json: samples[1].shutter_s: must be in [1e-06, 60]");
  j = PlanToJson(SmallPlan());
  j["keyframes"][0]["focal_length_mm"] = 1e6;
  EXPECT_EQ(ReadError(j), "plan.json: keyframes[0].focal_length_mm: must be in [0.1, 100000]");
  j = PlanToJson(SmallPlan());
  j["camera"]["max_focal_length_mm"] = 10;  // below min_focal_length_mm 24
  EXPECT_EQ(ReadError(j), "plan.json: camera.max_focal_length_mm: must be >= min_focal_length_mm");
  j = PlanToJson(SmallPlan());
  j["camera"]["max_focus_rate_m_s"] = 0;  // a limit rates are divided by
  EXPECT_EQ(ReadError(j), "plan.json: camera.max_focus_rate_m_s: must be > 0");
}

TEST(PlanFileDomains, AnglesAndIntentBounded) {
  Json j = PlanToJson(SmallPlan());
  j["samples"][2]["gimbal_pitch_deg"] = -1e300;
  EXPECT_EQ(ReadError(j), "plan.json: samples[2].gimbal_pitch_deg: must be in [-360, 360]");
  j = PlanToJson(SmallPlan());
  j["shots"][0]["intent"] = Json{{"background_blur_px", 1e300}};
  EXPECT_EQ(ReadError(j), "plan.json: shots[0].intent.background_blur_px: must be in (0, 1e7], got 1e+300");
}

TEST(PlanFile, TheFocusModeAndItsRacksRoundTrip) {
  Trajectory plan = SmallPlan();
  plan.shots[0].intent.focus = "rack";
  plan.shots[0].intent.rack = {{0.5, 1.0, "b"}, {2.0, 0.5, "c"}};
  const Json j = PlanToJson(plan);
  EXPECT_EQ(j["shots"][0]["intent"]["focus"], "rack");
  const Trajectory read = PlanFromJson(j, "plan.json");
  ASSERT_EQ(read.shots[0].intent.rack.size(), 2u);
  EXPECT_EQ(read.shots[0].intent.rack[1].subject, "c");
  EXPECT_EQ(read.shots[0].intent.rack[1].at_s, 2.0);
  EXPECT_EQ(read.shots[0].intent.rack[1].duration_s, 0.5);
  EXPECT_EQ(PlanToJson(read).dump(), j.dump());
  Json bad = j;
  bad["shots"][0]["intent"]["focus"] = "auto";
  EXPECT_EQ(ReadError(bad),
            "plan.json: shots[0].intent.focus: unknown focus \"auto\" (follow, fixed, infinity, keys, rack)");
  bad = j;
  bad["shots"][0]["intent"]["focus"] = "follow";
  EXPECT_EQ(ReadError(bad), "plan.json: shots[0].intent.rack: a rack needs \"focus\": \"rack\"");
  bad = j;
  bad["shots"][0]["intent"]["rack"][1]["at_s"] = 0.1;
  EXPECT_EQ(ReadError(bad), "plan.json: shots[0].intent.rack[1].at_s: racks must be in time order");
  // A plan written before the focus was recorded still reads, with the mode unknown.
  bad = j;
  bad["shots"][0]["intent"].erase("focus");
  bad["shots"][0]["intent"].erase("rack");
  EXPECT_TRUE(PlanFromJson(bad, "plan.json").shots[0].intent.focus.empty());
}

TEST(PlanFile, TheRetimeOptInRoundTripsAndIsWrittenOnlyWhenTrue) {
  Trajectory plan = SmallPlan();
  EXPECT_FALSE(PlanToJson(plan)["shots"][0].contains("intent") &&
               PlanToJson(plan)["shots"][0]["intent"].contains("retime"));
  plan.shots[0].intent.retime = true;
  const Json j = PlanToJson(plan);
  EXPECT_EQ(j["shots"][0]["intent"]["retime"], true);
  EXPECT_TRUE(PlanFromJson(j, "plan.json").shots[0].intent.retime);
  Json bad = j;
  bad["shots"][0]["intent"]["retime"] = "yes";
  EXPECT_EQ(ReadError(bad).rfind("plan.json: shots[0].intent.retime: ", 0), 0u) << ReadError(bad);
}

TEST(PlanFileDrone, AMissingFieldIsTheNamedProfilesAndSaysSo) {
  Trajectory plan = SmallPlan();
  plan.drone = *FindDroneProfile("dji-m30");
  Json j = PlanToJson(plan);
  EXPECT_TRUE(PlanFromJson(j, "plan.json").notes.empty());
  j["drone"].erase("max_gimbal_pitch_deg");
  const Trajectory read = PlanFromJson(j, "plan.json");
  EXPECT_EQ(read.drone.max_gimbal_pitch_deg, FindDroneProfile("dji-m30")->max_gimbal_pitch_deg);
  ASSERT_EQ(read.notes.size(), 1u);
  EXPECT_EQ(read.notes[0],
            "plan.json: drone.max_gimbal_pitch_deg: missing; the profile \"dji-m30\"'s value 45 is used");
  // No drone block at all: the default profile, said so.
  j.erase("drone");
  const Trajectory no_block = PlanFromJson(j, "plan.json");
  EXPECT_EQ(no_block.drone.name, DefaultDroneProfile().name);
  EXPECT_EQ(no_block.notes,
            std::vector<std::string>{"plan.json: drone: missing; the profile \"px4-multirotor\" is used"});
}

TEST(PlanFileDrone, AMissingFieldWithoutAProfileToTakeItFromIsRefused) {
  Json j = PlanToJson(SmallPlan());  // drone "custom": no registry profile of that name
  j["drone"].erase("max_gimbal_pitch_deg");
  EXPECT_EQ(ReadError(j),
            "plan.json: drone.max_gimbal_pitch_deg: missing, and \"custom\" is not a drone profile to take "
            "it from (docs/drones.md lists the profiles and the fields)");
  j = PlanToJson(SmallPlan());
  j["drone"]["max_jerk_m_s3"] = 1e300;
  EXPECT_EQ(ReadError(j), "plan.json: drone.max_jerk_m_s3: must lie within [-1e7, 1e7]");
  j["drone"]["max_jerk_m_s3"] = 1e-300;
  EXPECT_EQ(ReadError(j), "plan.json: drone.max_jerk_m_s3: must be at least 1e-6");
}

TEST(PlanFileDomains, TeamPlanKeysToo) {
  TeamPlan team;
  team.frame_rate_hz = 2;
  team.flights.push_back({"a", Eigen::Vector3d(1, 2, 3), SmallPlan()});
  team.flights.push_back({"b", std::nullopt, SmallPlan()});
  team.origin = team.flights[0].plan.origin;
  Json j = TeamPlanToJson(team);
  EXPECT_NO_THROW(TeamPlanFromJson(j, "plan.json"));
  j["flights"][0]["home_enu_m"][2] = 1e9;
  EXPECT_EQ(testing::InputErrorMessage([&] { TeamPlanFromJson(j, "plan.json"); }),
            "plan.json: flights[0].home_enu_m[2]: must lie within 1e7 m of the origin, got 1e+09");
  j = TeamPlanToJson(team);
  j["flights"][1]["samples"][0]["focal_length_mm"] = 0.01;
  EXPECT_EQ(testing::InputErrorMessage([&] { TeamPlanFromJson(j, "plan.json"); }),
            "plan.json: flights[1].samples[0].focal_length_mm: must be in [0.1, 100000]");
}

}  // namespace
}  // namespace cinepath
