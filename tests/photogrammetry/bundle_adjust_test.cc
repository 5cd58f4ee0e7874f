#include "photogrammetry/bundle_adjust.h"

#include <gtest/gtest.h>

#include "photogrammetry/camera_models.h"
#include "synthetic_colmap.h"

namespace cinepath::photogrammetry {
namespace {

// A synthetic survey in ENU, then "COLMAP's drift": the focal length grown by 25 % and every depth grown
// with it (the flat-scene valley), so that the images still fit.
ColmapModel Drifted(const ColmapModel& truth, double factor) {
  ColmapModel m = truth;
  for (auto& [id, cam] : m.cameras)
    for (int i : CameraModelFocalIndices(cam.model_id)) cam.params[i] *= factor;
  for (auto& [id, p] : m.points3d) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& e : p.track) {
      const auto& im = truth.images.at(e.image_id);
      Eigen::Vector3d xc = im.cam_from_world_rotation * p.xyz + im.cam_from_world_translation;
      xc.z() *= factor;
      sum += im.cam_from_world_rotation.conjugate() * (xc - im.cam_from_world_translation);
    }
    p.xyz = sum / static_cast<double>(p.track.size());
  }
  return m;
}

double MedianHeightError(const ColmapModel& a, const ColmapModel& truth) {
  std::vector<double> dz;
  for (const auto& [id, p] : a.points3d) dz.push_back(p.xyz.z() - truth.points3d.at(id).xyz.z());
  std::nth_element(dz.begin(), dz.begin() + dz.size() / 2, dz.end());
  return dz[dz.size() / 2];
}

TEST(BundleAdjust, FocalPriorAndGpsPutTheGroundBackAfterAFocalDrift) {
  testing::SyntheticOptions o;
  o.pixel_noise_px = 0.3;
  const auto scene = testing::MakeSyntheticScene(o);
  ColmapModel model = Drifted(scene.model_enu, 1.25);
  EXPECT_LT(MedianHeightError(model, scene.model_enu), -8.0);  // the drift: ground ~10 m low
  EXPECT_LT(RmsReprojectionErrorPx(model), 10.0);             // ... while the images still nearly fit
  std::map<uint32_t, Eigen::Vector3d> gps;
  for (size_t i = 0; i < scene.camera_centers_enu_m.size(); ++i) gps[i + 1] = scene.camera_centers_enu_m[i];
  const BundleAdjustReport r = BundleAdjustEnu(model, gps, {{1, 900.0}}, BundleAdjustOptions());
  EXPECT_NEAR(MedianHeightError(model, scene.model_enu), 0.0, 0.2);
  EXPECT_NEAR(r.focal[0].before_px, 1125, 1e-6);
  EXPECT_DOUBLE_EQ(r.focal[0].after_px, 900);
  EXPECT_TRUE(r.focal[0].held_at_prior);
  EXPECT_LT(r.rms_reprojection_after_px, 0.5);
  EXPECT_EQ(r.num_gps_priors, 18);
  EXPECT_FALSE(r.geometry_resolves_focal);  // 3 m relief at 40 m, near-nadir
}

TEST(BundleAdjust, ObliqueViewsOfReliefAreRecognizedAsResolvingTheFocalLength) {
  testing::SyntheticOptions o;
  o.terrain_relief_m = 12;
  const auto scene = testing::MakeSyntheticScene(o);
  ColmapModel model = scene.model_enu;
  // Tilt every other camera by 30 degrees about its x axis (oblique views), keeping its centre.
  for (auto& [id, im] : model.images) {
    if (id % 2) continue;
    const Eigen::Vector3d c = im.ProjectionCenter();
    im.cam_from_world_rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX())) * im.cam_from_world_rotation;
    im.cam_from_world_translation = -(im.cam_from_world_rotation * c);
  }
  // Observations must match the new poses: re-project each track element.
  for (auto& [pid, p] : model.points3d) {
    for (const auto& e : p.track) {
      auto& im = model.images.at(e.image_id);
      const Eigen::Vector3d xc = im.cam_from_world_rotation * p.xyz + im.cam_from_world_translation;
      double x = 0, y = 0;
      ProjectNormalizedToPixel(o.model_id, o.params.data(), xc.x() / xc.z(), xc.y() / xc.z(), &x, &y);
      im.points2d_px[e.point2d_idx] = {x, y};
    }
  }
  std::map<uint32_t, Eigen::Vector3d> gps;
  for (const auto& [id, im] : model.images) gps[id] = im.ProjectionCenter();
  BundleAdjustOptions options;
  options.profile_focal = true;
  const BundleAdjustReport r = BundleAdjustEnu(model, gps, {}, options);
  EXPECT_GT(r.view_axis_spread_deg, 14.0);
  EXPECT_NEAR(r.focal[0].after_px, 900, 9);
  ASSERT_TRUE(r.focal[0].images_sigma_ratio);
}

}  // namespace
}  // namespace cinepath::photogrammetry
