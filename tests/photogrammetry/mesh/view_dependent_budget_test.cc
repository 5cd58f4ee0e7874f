#include "photogrammetry/mesh/view_dependent_budget.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

// A camera at `center` looking north (+y), level: x right = east, y down, z forward = north.
PlanCamera NorthCamera(const Eigen::Vector3d& center, double focal_px) {
  PlanCamera c;
  c.center_enu_m = center;
  Eigen::Matrix3d world_from_camera;
  world_from_camera.col(0) = Eigen::Vector3d::UnitX();
  world_from_camera.col(1) = -Eigen::Vector3d::UnitZ();
  world_from_camera.col(2) = Eigen::Vector3d::UnitY();
  c.camera_from_world = world_from_camera.transpose();
  c.focal_px = focal_px;
  c.width_px = 1000;
  c.height_px = 500;
  return c;
}

TEST(ViewDependentBudget, OnAxisPointGetsDepthOverFocal) {
  const std::vector<PlanCamera> cameras = {NorthCamera(Eigen::Vector3d::Zero(), 1000)};
  const PointView v = FinestView(Eigen::Vector3d(0, 10, 0), cameras);
  ASSERT_TRUE(v.seen());
  EXPECT_EQ(v.camera, 0);
  EXPECT_NEAR(v.depth_m, 10, 1e-12);
  EXPECT_NEAR(v.metres_per_px, 10.0 / 1000, 1e-12);
}

TEST(ViewDependentBudget, OffAxisPointIsFinerThanDepthOverFocal) {
  const std::vector<PlanCamera> cameras = {NorthCamera(Eigen::Vector3d::Zero(), 1000)};
  // 4 m east at 10 m depth: u = 1000 * 0.4 + 500 = 900 px, inside.
  const PointView v = FinestView(Eigen::Vector3d(4, 10, 0), cameras);
  ASSERT_TRUE(v.seen());
  EXPECT_NEAR(v.metres_per_px, 100.0 / (1000 * std::sqrt(116.0)), 1e-12);
  EXPECT_LT(v.metres_per_px, 10.0 / 1000);
}

TEST(ViewDependentBudget, OutsideTheFrustumOrBehindIsUnseen) {
  const std::vector<PlanCamera> cameras = {NorthCamera(Eigen::Vector3d::Zero(), 1000)};
  EXPECT_FALSE(FinestView(Eigen::Vector3d(6, 10, 0), cameras).seen());   // u = 1100 > 1000
  EXPECT_FALSE(FinestView(Eigen::Vector3d(0, 10, 3), cameras).seen());   // v = -50 (above the image)
  EXPECT_FALSE(FinestView(Eigen::Vector3d(0, -10, 0), cameras).seen());  // behind
  EXPECT_TRUE(std::isinf(FinestView(Eigen::Vector3d(0, -10, 0), cameras).metres_per_px));
}

TEST(ViewDependentBudget, TheClosestOrLongestLensWins) {
  // Camera 1 is 5 m closer; camera 2 is as far as camera 0 but with a 3x longer lens.
  const std::vector<PlanCamera> cameras = {NorthCamera(Eigen::Vector3d(0, 0, 0), 1000),
                                           NorthCamera(Eigen::Vector3d(0, 5, 0), 1000),
                                           NorthCamera(Eigen::Vector3d(0, 0, 0), 3000)};
  const PointView v = FinestView(Eigen::Vector3d(0, 20, 0), cameras);
  EXPECT_EQ(v.camera, 2);
  EXPECT_NEAR(v.metres_per_px, 20.0 / 3000, 1e-12);
  const std::vector<PlanCamera> two(cameras.begin(), cameras.begin() + 2);
  EXPECT_EQ(FinestView(Eigen::Vector3d(0, 20, 0), two).camera, 1);
  const std::vector<PointView> views = FinestViews({Eigen::Vector3d(0, 20, 0), Eigen::Vector3d(0, -20, 0)}, two);
  ASSERT_EQ(views.size(), 2u);
  EXPECT_EQ(views[0].camera, 1);
  EXPECT_FALSE(views[1].seen());
}

TEST(ViewDependentBudget, CamerasFromPlanUseTheSensorWidthAndEachSamplesLens) {
  Trajectory plan;
  plan.camera.sensor_width_mm = 24.0;
  plan.camera.width_px = 4800;
  plan.camera.height_px = 2700;
  TrajectorySample s;
  s.focal_length_mm = 50;
  s.position_enu_m = Eigen::Vector3d(1, 2, 3);
  plan.samples = {s, s};
  plan.samples[1].focal_length_mm = 100;
  plan.samples[1].time_s = 1.0 / 30;
  const std::vector<PlanCamera> cameras = CamerasFromPlan(plan, "plan.json");
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_NEAR(cameras[0].focal_px, 10000, 1e-9);
  EXPECT_NEAR(cameras[1].focal_px, 20000, 1e-9);
  EXPECT_EQ(cameras[1].sample_index, 1);
  EXPECT_EQ(cameras[0].center_enu_m, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(cameras[0].width_px, 4800);
  plan.samples.clear();
  EXPECT_THROW(CamerasFromPlan(plan, "plan.json"), InputError);
}

}  // namespace
}  // namespace cinepath::photogrammetry
