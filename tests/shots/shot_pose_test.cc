#include "shots/shot_pose.h"

#include <gtest/gtest.h>

#include "core/angles.h"

namespace cinepath::shots {
namespace {

ShotList List(const std::string& shot) {
  return ParseShotList(
      Json::parse(
          R"({"schema": "cinepath.shots/1", "camera": {"min_focal_length_mm": 24, "sensor_width_mm": 36,
            "sensor_height_mm": 24},
      "actors": [{"name": "car", "height_m": 1.5, "interpolation": "linear", "keyframes": [
        {"time_s": 0, "position_enu_m": [0, 0, 0]}, {"time_s": 10, "position_enu_m": [100, 0, 0]}]}],
      "shots": [)" +
          shot + "]}"),
      "shots.json");
}

TEST(ShotPose, BearingsAreCompass) {
  EXPECT_NEAR((HorizontalFromBearing(0) - Eigen::Vector3d(0, 1, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((HorizontalFromBearing(90) - Eigen::Vector3d(1, 0, 0)).norm(), 0, 1e-15);
}

TEST(ShotPose, ChaseSitsBehindTheCarWithLag) {
  const ShotList l = List(
      R"({"type": "CHASE", "subject": "car", "duration_s": 10, "distance_m": 20, "height_m": 5, "lateral_m": 2,
        "lag_s": 1})");
  const ShotPose p = EvaluateShotPose(l.shots[0], l, 0, 5);
  // Car travels east at 10 m/s; at t - lag = 4 s it is at x = 40: behind = west, right = south.
  EXPECT_NEAR((p.position_enu_m - Eigen::Vector3d(20, -2, 5)).norm(), 0, 1e-9);
  EXPECT_NEAR((*p.aim_point_enu_m - Eigen::Vector3d(50, 0, 0.75)).norm(), 0, 1e-9);
}

TEST(ShotPose, FlybyPassesAtTheClosestDistanceMidShot) {
  const ShotList l = List(
      R"({"type": "FLYBY", "subject": "car", "duration_s": 8, "closest_distance_m": 12, "side": "left",
        "height_m": 3, "speed_m_s": 4})");
  const ShotPose mid = EvaluateShotPose(l.shots[0], l, 0, 4);
  EXPECT_NEAR((mid.position_enu_m - Eigen::Vector3d(40, 12, 3)).norm(), 0, 1e-9);  // left of an eastbound car = north
  const ShotPose start = EvaluateShotPose(l.shots[0], l, 0, 0);
  EXPECT_NEAR((start.position_enu_m - Eigen::Vector3d(0 - 16, 12, 3)).norm(), 0, 1e-9);  // 4 m/s x 4 s behind
}

TEST(ShotPose, DronieRampsDistanceAndHeight) {
  const ShotList l = List(
      R"({"type": "DRONIE", "subject": "car", "duration_s": 10, "distance_m": 10, "distance_end_m": 30,
        "height_m": 2, "height_end_m": 22, "bearing_deg": 180})");
  const ShotPose p = EvaluateShotPose(l.shots[0], l, 0, 5);  // linear easing: halfway
  EXPECT_NEAR((p.position_enu_m - Eigen::Vector3d(50, -20, 12)).norm(), 0, 1e-9);
  EXPECT_NEAR(p.eased, 0.5, 1e-15);
}

}  // namespace
}  // namespace cinepath::shots
