#include "core/plan_file.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"

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

}  // namespace
}  // namespace cinepath
