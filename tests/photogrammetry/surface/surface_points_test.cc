#include "photogrammetry/surface/surface_points.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

TEST(FilterPoints, DropsLargeErrorsShortTracksAndNonFinitePoints) {
  PointCloud cloud = testing::TerrainCloud(10, 10, 1.0);
  cloud.reprojection_error_px[3] = 5.0;
  cloud.reprojection_error_px[4] = 2.0;  // at the limit: kept
  cloud.observers[7] = {0, 1};
  cloud.observers[8] = {2};
  cloud.positions_m[9].x() = std::nan("");
  PointFilterReport report;
  const PointCloud out = FilterPoints(cloud, PointFilterOptions{}, &report);
  EXPECT_EQ(report.points_in, 100);
  EXPECT_EQ(report.removed_reprojection, 1);
  EXPECT_EQ(report.removed_short_track, 2);
  EXPECT_EQ(report.removed_non_finite, 1);
  EXPECT_EQ(report.points_out, 96);
  ASSERT_EQ(out.size(), 96u);
  EXPECT_EQ(out.colors_rgb.size(), 96u);
  EXPECT_EQ(out.observers.size(), 96u);
  EXPECT_EQ(out.camera_centers_m.size(), 4u);
  EXPECT_EQ(out.positions_m[3], cloud.positions_m[4]);
}

TEST(FilterPoints, SkipsCriteriaWithoutDataAndRejectsMisalignedAttributes) {
  PointCloud cloud;
  cloud.positions_m = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  PointFilterReport report;
  EXPECT_EQ(FilterPoints(cloud, PointFilterOptions{}, &report).size(), 3u);
  cloud.colors_rgb = {{1, 2, 3}};
  EXPECT_THROW(FilterPoints(cloud, PointFilterOptions{}, &report), InputError);
}

TEST(LooksLikeNadirCapture, CamerasAboveAreNadirCamerasAtTheSideAreNot) {
  PointCloud cloud = testing::TerrainCloud(10, 10, 1.0);
  EXPECT_TRUE(LooksLikeNadirCapture(cloud));
  for (auto& c : cloud.camera_centers_m) c = Eigen::Vector3d(c.x() + 500.0, c.y(), 0.0);
  EXPECT_FALSE(LooksLikeNadirCapture(cloud));
  // Without cameras: a flat, wide cloud is nadir-like, a tall thin one is not.
  PointCloud flat = testing::TerrainCloud(10, 10, 1.0);
  flat.observers.clear();
  flat.camera_centers_m.clear();
  EXPECT_TRUE(LooksLikeNadirCapture(flat));
  for (auto& p : flat.positions_m) std::swap(p.y(), p.z());
  for (auto& p : flat.positions_m) p.z() *= 10;
  EXPECT_FALSE(LooksLikeNadirCapture(flat));
}

}  // namespace
}  // namespace cinepath::photogrammetry
