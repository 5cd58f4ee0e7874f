#include "photogrammetry/georef/camera_models.h"

#include <gtest/gtest.h>

#include <ceres/jet.h>

#include "core/error.h"
#include "photogrammetry/io/colmap_reader.h"
#include "tests/photogrammetry/test_paths.h"

namespace cinepath::photogrammetry {
namespace {

TEST(CameraModels, IdsNamesAndParameterCountsAreCOLMAP38s) {
  const std::pair<const char*, int> expected[] = {{"SIMPLE_PINHOLE", 3},
                                                  {"PINHOLE", 4},
                                                  {"SIMPLE_RADIAL", 4},
                                                  {"RADIAL", 5},
                                                  {"OPENCV", 8},
                                                  {"OPENCV_FISHEYE", 8},
                                                  {"FULL_OPENCV", 12},
                                                  {"FOV", 5},
                                                  {"SIMPLE_RADIAL_FISHEYE", 4},
                                                  {"RADIAL_FISHEYE", 5},
                                                  {"THIN_PRISM_FISHEYE", 12}};
  for (int id = 0; id < 11; ++id) {
    EXPECT_EQ(CameraModelName(id), expected[id].first);
    EXPECT_EQ(CameraModelNumParams(id), expected[id].second);
    EXPECT_EQ(CameraModelIdFromName(expected[id].first), id);
  }
  EXPECT_FALSE(IsKnownCameraModel(11));
  EXPECT_FALSE(IsKnownCameraModel(-1));
  EXPECT_EQ(CameraModelNumParams(11), 0);
  EXPECT_FALSE(CameraModelIdFromName("EQUIRECTANGULAR"));
}

std::vector<double> ParamsFor(int id) {
  std::vector<double> p(CameraModelNumParams(id), 0.0);
  const bool single = CameraModelHasSingleFocal(id);
  p[0] = 1000;
  if (!single) p[1] = 990;
  p[single ? 1 : 2] = 640;
  p[single ? 2 : 3] = 480;
  int k = 0;
  for (int i : CameraModelExtraIndices(id)) p[i] = (k++ % 2 ? -0.01 : 0.02);
  if (id == static_cast<int>(CameraModelId::kFov)) p[4] = 0.8;
  return p;
}

TEST(CameraModels, ZeroDistortionIsThePinholeOrEquidistantMap) {
  const double u = 0.2, v = -0.1, r = std::hypot(u, v);
  for (int id = 0; id < kNumCameraModels; ++id) {
    if (id == static_cast<int>(CameraModelId::kFov)) continue;  // FOV's omega = 0 is the pinhole too
    std::vector<double> p = ParamsFor(id);
    for (int i : CameraModelExtraIndices(id)) p[i] = 0;
    double x, y;
    ASSERT_TRUE(ProjectNormalizedToPixel(id, p.data(), u, v, &x, &y));
    const bool fisheye = std::string_view(CameraModelName(id)).find("FISHEYE") != std::string_view::npos;
    const double s = fisheye ? std::atan(r) / r : 1.0;
    const bool single = CameraModelHasSingleFocal(id);
    const double fy = single ? p[0] : p[1];
    EXPECT_NEAR(x, p[0] * u * s + (single ? p[1] : p[2]), 1e-9) << CameraModelName(id);
    EXPECT_NEAR(y, fy * v * s + (single ? p[2] : p[3]), 1e-9) << CameraModelName(id);
  }
}

TEST(CameraModels, KnownValues) {
  // SIMPLE_RADIAL: x = f u (1 + k r^2) + cx.
  const double sr[] = {1000, 640, 480, 0.1};
  double x, y;
  ProjectNormalizedToPixel(2, sr, 0.3, 0.4, &x, &y);
  EXPECT_NEAR(x, 1000 * 0.3 * (1 + 0.1 * 0.25) + 640, 1e-9);
  EXPECT_NEAR(y, 1000 * 0.4 * (1 + 0.1 * 0.25) + 480, 1e-9);
  // OPENCV tangential term: du = 2 p1 u v + p2 (r^2 + 2 u^2).
  const double cv[] = {1000, 1000, 0, 0, 0, 0, 0.01, 0.02};
  ProjectNormalizedToPixel(4, cv, 0.3, 0.4, &x, &y);
  EXPECT_NEAR(x, 1000 * (0.3 + 2 * 0.01 * 0.12 + 0.02 * (0.25 + 0.18)), 1e-9);
  EXPECT_NEAR(y, 1000 * (0.4 + 2 * 0.02 * 0.12 + 0.01 * (0.25 + 0.32)), 1e-9);
  // FOV: factor = atan(r 2 tan(w/2)) / (r w).
  const double fov[] = {1000, 1000, 0, 0, 0.9};
  ProjectNormalizedToPixel(7, fov, 0.3, 0.4, &x, &y);
  const double factor = std::atan(0.5 * 2 * std::tan(0.45)) / (0.5 * 0.9);
  EXPECT_NEAR(x, 1000 * 0.3 * factor, 1e-9);
  // OPENCV_FISHEYE: theta_d = theta (1 + k1 theta^2 + ...), u' = u theta_d / r.
  const double fe[] = {1000, 1000, 0, 0, 0.05, 0, 0, 0};
  ProjectNormalizedToPixel(5, fe, 0.3, 0.4, &x, &y);
  const double theta = std::atan(0.5);
  EXPECT_NEAR(x, 1000 * 0.3 * theta * (1 + 0.05 * theta * theta) / 0.5, 1e-9);
}

TEST(CameraModels, UndistortionInvertsProjectionForEveryModel) {
  for (int id = 0; id < kNumCameraModels; ++id) {
    const auto p = ParamsFor(id);
    for (double u : {-0.4, 0.0, 0.25}) {
      for (double v : {-0.3, 0.1}) {
        double x, y, u2, v2;
        ASSERT_TRUE(ProjectNormalizedToPixel(id, p.data(), u, v, &x, &y));
        ASSERT_TRUE(PixelToNormalized(id, p, x, y, &u2, &v2)) << CameraModelName(id);
        EXPECT_NEAR(u2, u, 1e-8) << CameraModelName(id);
        EXPECT_NEAR(v2, v, 1e-8) << CameraModelName(id);
      }
    }
  }
}

TEST(CameraModels, JetsDifferentiateLikeFiniteDifferences) {
  using J = ceres::Jet<double, 2>;
  for (int id = 0; id < kNumCameraModels; ++id) {
    const auto p = ParamsFor(id);
    std::vector<J> pj(p.begin(), p.end());
    const J u(0.21, 0), v(-0.13, 1);
    J x, y;
    ASSERT_TRUE(ProjectNormalizedToPixel(id, pj.data(), u, v, &x, &y));
    const double h = 1e-6;
    double x1, y1, x0, y0;
    ProjectNormalizedToPixel(id, p.data(), 0.21 + h, -0.13, &x1, &y1);
    ProjectNormalizedToPixel(id, p.data(), 0.21 - h, -0.13, &x0, &y0);
    EXPECT_NEAR(x.v[0], (x1 - x0) / (2 * h), 1e-4) << CameraModelName(id);
    EXPECT_NEAR(y.v[0], (y1 - y0) / (2 * h), 1e-4) << CameraModelName(id);
  }
}

// COLMAP says its default Brighton Beach model has a 0.32 px mean reprojection error: our OPENCV
// projection of its points must agree.
TEST(CameraModels, BrightonBeachReprojectsAsCOLMAPReports) {
  const ColmapModel model = ReadColmapModel(testing::TestDataDir() / "colmap" / "brighton_sparse_default");
  double sum = 0;
  size_t n = 0;
  for (const auto& [id, point] : model.points3d) {
    for (const auto& e : point.track) {
      const auto& im = model.images.at(e.image_id);
      const auto& cam = model.cameras.at(im.camera_id);
      const Eigen::Vector3d xc = im.cam_from_world_rotation * point.xyz + im.cam_from_world_translation;
      double x, y;
      ProjectNormalizedToPixel(cam.model_id, cam.params.data(), xc.x() / xc.z(), xc.y() / xc.z(), &x, &y);
      sum += (Eigen::Vector2d(x, y) - im.points2d_px[e.point2d_idx]).norm();
      ++n;
    }
  }
  EXPECT_NEAR(sum / n, 0.32, 0.03);
}

}  // namespace
}  // namespace cinepath::photogrammetry
