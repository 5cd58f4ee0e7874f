#include "photogrammetry/georef/bundle_adjust.h"

#include <gtest/gtest.h>

#include "photogrammetry/georef/camera_models.h"
#include "photogrammetry/georef/georeference.h"
#include "tests/photogrammetry/synthetic_colmap.h"

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
  EXPECT_LT(RmsReprojectionErrorPx(model), 10.0);              // ... while the images still nearly fit
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

// The synthetic survey's cameras turned about their x axes, the odd image ids by `odd_rad`, the even ones by
// `even_rad`, their centres kept, the observations re-projected: oblique views.
ColmapModel Tilted(const testing::SyntheticOptions& o, const ColmapModel& truth, double odd_rad, double even_rad) {
  ColmapModel model = truth;
  for (auto& [id, im] : model.images) {
    const Eigen::Vector3d c = im.ProjectionCenter();
    const double angle = id % 2 ? odd_rad : even_rad;
    im.cam_from_world_rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX())) * im.cam_from_world_rotation;
    im.cam_from_world_translation = -(im.cam_from_world_rotation * c);
  }
  for (auto& [pid, p] : model.points3d) {
    for (const auto& e : p.track) {
      auto& im = model.images.at(e.image_id);
      const Eigen::Vector3d xc = im.cam_from_world_rotation * p.xyz + im.cam_from_world_translation;
      double x = 0, y = 0;
      ProjectNormalizedToPixel(o.model_id, o.params.data(), xc.x() / xc.z(), xc.y() / xc.z(), &x, &y);
      im.points2d_px[e.point2d_idx] = {x, y};
    }
  }
  return model;
}

TEST(BundleAdjust, ObliqueViewsOfReliefAreRecognizedAsResolvingTheFocalLength) {
  testing::SyntheticOptions o;
  o.terrain_relief_m = 12;
  const auto scene = testing::MakeSyntheticScene(o);
  ColmapModel model = Tilted(o, scene.model_enu, 0.0, 0.5);  // every other camera 30 degrees oblique
  std::map<uint32_t, Eigen::Vector3d> gps;
  for (const auto& [id, im] : model.images) gps[id] = im.ProjectionCenter();
  BundleAdjustOptions options;
  options.profile_focal = true;
  const BundleAdjustReport r = BundleAdjustEnu(model, gps, {}, options);
  EXPECT_GT(r.view_axis_spread_deg, 14.0);
  EXPECT_NEAR(r.focal[0].after_px, 900, 9);
  ASSERT_TRUE(r.focal[0].images_sigma_ratio);
}

// A survey of 12 m relief with exact GPS at the camera centres and an EXIF prior 6 % below the true
// 900 px (a 35 mm equivalent rounded by the camera).
struct ReliefSurvey {
  testing::SyntheticOptions o;
  testing::SyntheticScene scene;
  std::map<uint32_t, Eigen::Vector3d> gps;
  std::map<uint32_t, double> rounded_exif = {{1, 0.94 * 900}};
  ColmapModel Oblique() const { return Tilted(o, scene.model_enu, 0.6, -0.6); }  // every camera tilted 34 deg
  ReliefSurvey() {
    o.terrain_relief_m = 12;
    scene = testing::MakeSyntheticScene(o);
    for (const auto& [id, im] : scene.model_enu.images) gps[id] = im.ProjectionCenter();
  }
};

// Both sides of the focal-length rule, with an EXIF prior 6 % below the true 900 px (a 35 mm equivalent
// rounded by the camera). Oblique views of relief measure the focal length: it is kept, the prior only a
// weak pull. The flat nadir survey cannot: the focal length is held at the prior (the ambiguity of a
// flat scene seen from above).
TEST(BundleAdjust, TheFocalLengthThePhotosMeasureIsKeptWhereTheGeometryResolvesIt) {
  const ReliefSurvey survey;

  ColmapModel oblique = survey.Oblique();
  const BundleAdjustReport measured = BundleAdjustEnu(oblique, survey.gps, survey.rounded_exif, BundleAdjustOptions());
  EXPECT_TRUE(measured.geometry_resolves_focal);
  EXPECT_GT(measured.view_axis_spread_deg, 20.0);
  EXPECT_TRUE(measured.focal[0].measured_by_images);
  EXPECT_FALSE(measured.focal[0].held_at_prior);
  EXPECT_NEAR(measured.focal[0].after_px, 900, 4.5);  // within 0.5 % of the truth, 6 % from the prior
  EXPECT_LT(measured.rms_reprojection_after_px, 0.5);

  testing::SyntheticOptions flat;
  const auto nadir_scene = testing::MakeSyntheticScene(flat);
  ColmapModel nadir = nadir_scene.model_enu;
  const BundleAdjustReport held = BundleAdjustEnu(nadir, survey.gps, survey.rounded_exif, BundleAdjustOptions());
  EXPECT_FALSE(held.geometry_resolves_focal);
  EXPECT_FALSE(held.focal[0].measured_by_images);
  EXPECT_TRUE(held.focal[0].held_at_prior);
  EXPECT_DOUBLE_EQ(held.focal[0].after_px, 0.94 * 900);

  // Without the rule (the behaviour before it) the oblique views were held at the rounded prior too.
  BundleAdjustOptions old_rule;
  old_rule.keep_measured_focal = false;
  ColmapModel oblique_held = survey.Oblique();
  const BundleAdjustReport forced = BundleAdjustEnu(oblique_held, survey.gps, survey.rounded_exif, old_rule);
  EXPECT_DOUBLE_EQ(forced.focal[0].after_px, 0.94 * 900);
}

// The rule's boundary, from the two figures scene.json reports. The same oblique views of relief (EXIF
// prior 6 % low), with the thresholds put just above both measured figures and then just below one of
// them: above both, the views cannot separate focal length from depth and the focal length is held at the
// prior; below either one, the focal length the photos measure is kept. Which way the cameras look
// plays no part beyond these two figures.
TEST(BundleAdjust, TheFocalRuleDecidesFromDepthReliefAndViewSpreadAlone) {
  const ReliefSurvey survey;
  const ColmapModel oblique = survey.Oblique();

  ColmapModel probe = oblique;
  const BundleAdjustReport measured = BundleAdjustEnu(probe, survey.gps, survey.rounded_exif, BundleAdjustOptions());
  const double relief = measured.depth_relief_ratio, spread_deg = measured.view_axis_spread_deg;
  ASSERT_GT(relief, 0);
  ASSERT_GT(spread_deg, 0);

  BundleAdjustOptions above_both;
  above_both.min_depth_relief_ratio = relief * 1.05;
  above_both.min_view_axis_spread_deg = spread_deg + 0.5;
  ColmapModel held_model = oblique;
  const BundleAdjustReport held = BundleAdjustEnu(held_model, survey.gps, survey.rounded_exif, above_both);
  EXPECT_FALSE(held.geometry_resolves_focal);
  EXPECT_TRUE(held.focal[0].held_at_prior);
  EXPECT_DOUBLE_EQ(held.focal[0].after_px, 0.94 * 900);

  for (int which = 0; which < 2; ++which) {  // just below the spread threshold, then just below the relief one
    BundleAdjustOptions below_one = above_both;
    if (which == 0) below_one.min_view_axis_spread_deg = spread_deg - 0.5;
    if (which == 1) below_one.min_depth_relief_ratio = relief * 0.95;
    ColmapModel kept_model = oblique;
    const BundleAdjustReport kept = BundleAdjustEnu(kept_model, survey.gps, survey.rounded_exif, below_one);
    EXPECT_TRUE(kept.geometry_resolves_focal) << which;
    EXPECT_TRUE(kept.focal[0].measured_by_images) << which;
    EXPECT_FALSE(kept.focal[0].held_at_prior) << which;
    EXPECT_NEAR(kept.focal[0].after_px, 900, 4.5) << which;
  }
}

TEST(BundleAdjust, ControlPointsAloneHoldTheSceneWhereTheSurveySaysIt) {
  testing::SyntheticOptions o;
  o.pixel_noise_px = 0.3;
  const testing::SyntheticScene scene = testing::MakeSyntheticScene(o);
  // The model starts 1.5 m east, 0.8 m north and 0.6 m up of the truth, slightly rotated.
  Similarity3 offset;
  offset.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitZ()));
  offset.translation = {1.5, 0.8, 0.6};
  ColmapModel model = scene.model_enu;
  for (auto& [id, image] : model.images) {
    const Eigen::Vector3d c = offset(image.ProjectionCenter());
    image.cam_from_world_rotation = (image.cam_from_world_rotation * offset.rotation.conjugate()).normalized();
    image.cam_from_world_translation = -(image.cam_from_world_rotation * c);
  }
  for (auto& [id, p] : model.points3d) p.xyz = offset(p.xyz);
  // Four surveyed ground points with exact pixels in every image that sees them; no GPS at all.
  std::vector<ControlPointPrior> control;
  for (const Eigen::Vector2d en :
       {Eigen::Vector2d(-30, -10), Eigen::Vector2d(30, -10), Eigen::Vector2d(-25, 12), Eigen::Vector2d(28, 11)}) {
    ControlPointPrior c;
    c.target_enu_m = {en.x(), en.y(), testing::SyntheticGroundHeight(en.x(), en.y(), o.terrain_relief_m)};
    c.initial_enu_m = offset(c.target_enu_m);
    for (const auto& [id, image] : scene.model_enu.images) {
      const ColmapCamera& cam = scene.model_enu.cameras.at(1);
      const Eigen::Vector3d x = image.cam_from_world_rotation * c.target_enu_m + image.cam_from_world_translation;
      double px, py;
      ProjectNormalizedToPixel(cam.model_id, cam.params.data(), x.x() / x.z(), x.y() / x.z(), &px, &py);
      if (px > 0 && py > 0 && px < cam.width_px && py < cam.height_px) c.observations.push_back({id, {px, py}});
    }
    ASSERT_GE(c.observations.size(), 2u);
    control.push_back(c);
  }
  BundleAdjustOptions options;
  options.profile_focal = false;
  std::vector<Eigen::Vector3d> adjusted;
  const BundleAdjustReport report = BundleAdjustEnu(model, {}, {{1, 900.0}}, options, control, &adjusted);
  EXPECT_EQ(report.num_control_points, 4);
  EXPECT_EQ(report.num_gps_priors, 0);
  ASSERT_EQ(adjusted.size(), 4u);
  for (size_t k = 0; k < 4; ++k) EXPECT_LT((adjusted[k] - control[k].target_enu_m).norm(), 0.03) << k;
  double worst = 0;
  for (const auto& [id, image] : model.images) {
    worst = std::max(worst, (image.ProjectionCenter() - scene.camera_centers_enu_m[id - 1]).norm());
  }
  EXPECT_LT(worst, 0.1);  // from 1.7 m off
}

}  // namespace
}  // namespace cinepath::photogrammetry
