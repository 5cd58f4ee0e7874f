#include "core/reframe.h"

#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace cinepath {
namespace {

TEST(Reframe, PositionsKeepTheirPlaceOnEarthAndDirectionsTheirBearing) {
  Trajectory plan;
  plan.origin = Geodetic{46.84265, -91.99445, 153.0};
  TrajectorySample s;
  s.position_enu_m = Eigen::Vector3d(120, -250, 30);
  s.world_from_camera = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  plan.samples.push_back(s);
  plan.subjects.push_back({"a", 1.8, {Eigen::Vector3d(5, 6, 7)}});
  const Geodetic scene{46.842656667, -91.994008025, 198.5534};
  const Trajectory moved = ReframeToOrigin(plan, scene);
  const EnuFrame plan_frame(*plan.origin), scene_frame(scene);
  const Geodetic where = plan_frame.GeodeticFromEnu(s.position_enu_m);
  EXPECT_LT((moved.samples[0].position_enu_m - scene_frame.EnuFromGeodetic(where)).norm(), 1e-8);
  // Here the origins are 34 m apart in longitude and 45.6 m in height: the shift is about that.
  EXPECT_NEAR(moved.samples[0].position_enu_m.z() - s.position_enu_m.z(), 153.0 - 198.5534, 0.01);
  // A camera direction points at the same place on earth from both frames.
  const Eigen::Vector3d forward_plan = s.world_from_camera * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d target_plan = s.position_enu_m + 1000 * forward_plan;
  const Eigen::Vector3d target_scene = scene_frame.EnuFromGeodetic(plan_frame.GeodeticFromEnu(target_plan));
  const Eigen::Vector3d forward_scene = moved.samples[0].world_from_camera * Eigen::Vector3d::UnitZ();
  EXPECT_LT((moved.samples[0].position_enu_m + 1000 * forward_scene - target_scene).norm(), 1e-6);
  EXPECT_LT((moved.subjects[0].positions_enu_m[0] -
             scene_frame.EnuFromGeodetic(plan_frame.GeodeticFromEnu(Eigen::Vector3d(5, 6, 7))))
                .norm(),
            1e-8);
  EXPECT_EQ(moved.origin->height_m, scene.height_m);
}

TEST(Reframe, APlanWithoutAnOriginIsLeftAsItIs) {
  Trajectory plan;
  plan.samples.emplace_back();
  plan.samples[0].position_enu_m = Eigen::Vector3d(1, 2, 3);
  EXPECT_EQ(ReframeToOrigin(plan, Geodetic{10, 20, 30}).samples[0].position_enu_m, Eigen::Vector3d(1, 2, 3));
}

// The motion that moves a scene's mesh into a shot list's frame puts every point where the two frames'
// geodetic conversions put it, near and kilometres from either origin, and across the antimeridian.
TEST(Reframe, EnuFromEnuMovesPointsToTheSamePlaceOnEarth) {
  const std::vector<std::pair<Geodetic, Geodetic>> cases = {
      {{46.842656667, -91.994008025, 198.5534}, {46.84265, -91.99445, 153.0}},  // 34 m and 45.6 m apart
      {{47.3769, 8.5417, 448.0002}, {47.3769, 8.5417, 420.0}},                  // one above the other
      {{89.95, 10.0, 0.0}, {89.95, -170.0, 30.0}},                              // 11 km across the pole
      {{-33.9, 179.999, 5.0}, {-33.91, -179.99, 12.0}}};                        // across the antimeridian
  for (const auto& [from, to] : cases) {
    const EnuFrame source(from), target(to);
    const Eigen::Isometry3d motion = EnuFromEnu(to, from);
    for (const Eigen::Vector3d p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(120, -250, 30),
                                    Eigen::Vector3d(-3000, 1500, -40), Eigen::Vector3d(0, 0, 500)}) {
      const Eigen::Vector3d expected = target.EnuFromGeodetic(source.GeodeticFromEnu(p));
      EXPECT_LT((motion * p - expected).norm(), 1e-6) << p.transpose();
    }
    // Rigid: lengths and angles are kept.
    EXPECT_LT((motion.linear() * motion.linear().transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    EXPECT_NEAR(motion.linear().determinant(), 1.0, 1e-12);
  }
  // The same origin: no motion.
  const Geodetic o{46.84265, -91.99445, 153.0};
  EXPECT_LT((EnuFromEnu(o, o).matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-9);
}

}  // namespace
}  // namespace cinepath
