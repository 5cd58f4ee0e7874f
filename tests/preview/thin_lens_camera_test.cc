#include "preview/thin_lens_camera.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "core/optics.h"

namespace cinepath::preview {
namespace {

// Looking north, level: camera x -> east, y -> down, z -> north.
CameraPose LookingNorth() {
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  return {Eigen::Vector3d(10, -20, 5), Eigen::Quaterniond(r)};
}

TEST(ThinLensCamera, ProjectInvertsThePinholeRayAndUsesTheSensorFit) {
  CameraSpec spec;  // Super 35, 24.89 x 18.67 mm, 3840 x 2160
  const ThinLensCamera camera(spec, 3840, 2160, 35, 2.8, 10);
  const CameraPose pose = LookingNorth();
  const CameraRay ray = camera.Ray(pose, 100.25, 2000.5);
  double depth = 0;
  const Eigen::Vector2d xy = camera.Project(pose, ray.origin_enu_m + 7 * ray.direction_enu, &depth);
  EXPECT_NEAR(xy.x(), 100.25, 1e-9);
  EXPECT_NEAR(xy.y(), 2000.5, 1e-9);
  EXPECT_GT(depth, 0);
  // The top edge of the image looks up by atan(h/2 / f) with h = w * 2160/3840 = 14.0 mm, not 18.67.
  const CameraRay top = camera.Ray(pose, 1920, 0);
  const double up_deg = std::asin(top.direction_enu.z()) * 180 / M_PI;
  EXPECT_NEAR(up_deg, std::atan(24.89 * 2160 / 3840 / 2 / 35) * 180 / M_PI, 1e-9);
}

// Through a CameraFrame (the rotation as a matrix) a point lands where it does through the pose, for any
// rotation and points in front of, beside and behind the camera.
TEST(ThinLensCamera, ProjectThroughAFrameAgreesWithThePose) {
  CameraSpec spec;
  const ThinLensCamera camera(spec, 1920, 1080, 24, 4, 30);
  const CameraPose pose{Eigen::Vector3d(120.5, -3400.25, 87),
                        Eigen::Quaterniond(0.3, -0.5, 0.7, 0.2).normalized()};  // an arbitrary rotation
  const CameraFrame frame(pose);
  uint32_t state = 7;
  auto uniform = [&] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1 << 24) * 2 - 1;
  };
  for (int n = 0; n < 1000; ++n) {
    const Eigen::Vector3d point = pose.position_enu_m + 500 * Eigen::Vector3d(uniform(), uniform(), uniform());
    double depth_pose = 0, depth_frame = 0;
    const Eigen::Vector2d by_pose = camera.Project(pose, point, &depth_pose);
    const Eigen::Vector2d by_frame = camera.Project(frame, point, &depth_frame);
    ASSERT_NEAR(depth_frame, depth_pose, 1e-9) << n;
    if (std::abs(depth_pose) > 1) ASSERT_LT((by_frame - by_pose).norm(), 1e-6) << n;
  }
}

// PinholeRays gives Ray()'s pinhole rays through the pixel centres to the bit, for any rotation, lens and
// image size (the render's frames depend on it).
TEST(PinholeRays, AreThePixelCentresPinholeRaysToTheBit) {
  CameraSpec spec;
  uint32_t state = 3;
  auto uniform = [&] {
    state = state * 1664525u + 1013904223u;
    return double(state >> 8) / double(1 << 24) * 2 - 1;
  };
  for (int trial = 0; trial < 20; ++trial) {
    const int w = 40 + trial * 7, h = 30 + trial * 3;
    const ThinLensCamera camera(spec, w, h, trial % 2 ? 4.5 : 1200, 2.8, 10);
    const CameraPose pose{Eigen::Vector3d(uniform(), uniform(), uniform()) * 3000,
                          Eigen::Quaterniond(uniform(), uniform(), uniform(), uniform()).normalized()};
    const CameraFrame frame(pose);
    const PinholeRays rays(camera, frame);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const CameraRay expected = camera.Ray(frame, x + 0.5, y + 0.5);
        const CameraRay got = rays.At(x, y);
        ASSERT_EQ(got.origin_enu_m, expected.origin_enu_m);
        ASSERT_EQ(got.direction_enu, expected.direction_enu) << trial << " at " << x << ", " << y;
      }
    }
  }
}

TEST(ThinLensCamera, LensRaysMeetOnThePlaneOfFocus) {
  CameraSpec spec;
  const ThinLensCamera camera(spec, 640, 360, 85, 1.4, 12);
  const CameraPose pose = LookingNorth();
  const CameraRay centre = camera.Ray(pose, 300, 100);
  const Eigen::Vector3d on_focus_plane = centre.origin_enu_m + centre.direction_enu * (12 / centre.direction_enu.y());
  for (const auto& [u, v] : {std::pair{1.0, 0.0}, {0.0, -1.0}, {0.6, 0.8}}) {
    const CameraRay ray = camera.Ray(pose, 300, 100, u, v);
    EXPECT_NEAR((ray.origin_enu_m - centre.origin_enu_m).norm(), 0.085 / 1.4 / 2, 1e-12);
    const double t = (on_focus_plane.y() - ray.origin_enu_m.y()) / ray.direction_enu.y();
    EXPECT_LT((ray.origin_enu_m + t * ray.direction_enu - on_focus_plane).norm(), 1e-9);
  }
}

TEST(ThinLensCamera, BlurIsCoresBlurCircleTimesTheRayTracersFactor) {
  CameraSpec spec;
  const ThinLensCamera camera(spec, 1000, 500, 50, 2, 5);
  const double expected = BlurCircleMm(50, 2, 5, 20) * (5 - 0.05) / 5 * 1000 / spec.sensor_width_mm;
  EXPECT_NEAR(camera.BlurPx(20), expected, 1e-12);
  EXPECT_NEAR(camera.BlurPx(5), 0, 1e-12);
  const ThinLensCamera at_infinity(spec, 1000, 500, 50, 2, std::numeric_limits<double>::infinity());
  EXPECT_NEAR(at_infinity.BlurPx(std::numeric_limits<double>::infinity()), 0, 1e-12);
  EXPECT_NEAR(at_infinity.BlurPx(100), 50.0 * 50 / 2 / 100000 * 1000 / spec.sensor_width_mm, 1e-9);
}

// BlurPx keeps the lens's terms from its constructor: the same bits as core's formula evaluated whole,
// for 4-1200 mm lenses, focus near and at infinity, depths from the lens to 100 km.
TEST(ThinLensCamera, BlurIsCoresFormulaToTheBit) {
  CameraSpec spec;
  for (const double focal_mm : {4.0, 24.0, 85.0, 1200.0}) {
    for (const double f_number : {1.0, 2.8, 16.0}) {
      for (const double focus_m : {1.3, 7.5, 250.0, std::numeric_limits<double>::infinity()}) {
        const ThinLensCamera camera(spec, 640, 360, focal_mm, f_number, focus_m);
        for (double depth_m = 1e-3; depth_m < 1e5; depth_m *= 1.37) {
          double expected = 0;
          if (depth_m > focal_mm / 1000) {
            expected = BlurCircleDiameterM(focal_mm / 1000.0, f_number, 1.0 / focus_m, 1.0 / depth_m) * 1000.0 *
                       (std::isinf(focus_m) ? 1.0 : (focus_m - focal_mm / 1000) / focus_m) * camera.pixels_per_mm();
          }
          ASSERT_EQ(camera.BlurPx(depth_m), expected) << focal_mm << " mm f/" << f_number << " at " << focus_m;
        }
      }
    }
  }
}

TEST(ThinLensCamera, ConcentricDiskStaysOnTheDiskAndCoversIt) {
  double max_r = 0;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j) max_r = std::max(max_r, ConcentricDisk(i / 20.0, j / 20.0).norm());
  }
  EXPECT_NEAR(max_r, 1.0, 1e-12);
  EXPECT_NEAR(ConcentricDisk(0.5, 0.5).norm(), 0.0, 1e-12);
}

TEST(ThinLensCamera, PoseAtInterpolatesBetweenSamples) {
  Trajectory plan;
  plan.samples.resize(2);
  plan.samples[0].time_s = 0;
  plan.samples[1].time_s = 1;
  plan.samples[1].position_enu_m = Eigen::Vector3d(10, 0, 0);
  plan.samples[1].world_from_camera = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const CameraPose mid = PoseAt(plan, 0.25);
  EXPECT_NEAR(mid.position_enu_m.x(), 2.5, 1e-12);
  EXPECT_NEAR(mid.world_from_camera.angularDistance(Eigen::Quaterniond::Identity()), M_PI / 8, 1e-12);
  EXPECT_NEAR(PoseAt(plan, 9).position_enu_m.x(), 10, 1e-12);
}

TEST(ThinLensCamera, SampleAfterIsUpperBoundWhateverTheHint) {
  std::vector<TrajectorySample> samples(40);
  for (size_t i = 0; i < samples.size(); ++i) samples[i].time_s = double(i / 2) * 0.5;  // pairs of equal times
  const auto later = [](double t, const TrajectorySample& s) { return t < s.time_s; };
  for (size_t n : {size_t(1), size_t(7), samples.size()}) {
    for (double t = -1; t < 12; t += 0.125) {
      const size_t expected =
          size_t(std::upper_bound(samples.begin(), samples.begin() + long(n), t, later) - samples.begin());
      for (size_t hint = 0; hint < samples.size() + 3; ++hint) {
        ASSERT_EQ(SampleAfter(samples, n, t, hint), expected) << "n " << n << " t " << t << " hint " << hint;
      }
    }
  }
}

}  // namespace
}  // namespace cinepath::preview
