#include "photogrammetry/georef/triangulation.h"

#include <gtest/gtest.h>

#include <random>

#include "photogrammetry/georef/camera_models.h"
#include "tests/photogrammetry/synthetic_colmap.h"

namespace cinepath::photogrammetry {
namespace {

// Projects an ENU point into every image of the scene that sees it (COLMAP frame model), with noise.
std::vector<PixelObservation> Observe(const testing::SyntheticScene& scene, const Eigen::Vector3d& x_colmap,
                                      double noise_px, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0, noise_px);
  std::vector<PixelObservation> obs;
  for (const auto& [id, image] : scene.model.images) {
    const ColmapCamera& cam = scene.model.cameras.at(image.camera_id);
    const Eigen::Vector3d c = image.cam_from_world_rotation * x_colmap + image.cam_from_world_translation;
    if (c.z() <= 0) continue;
    double px, py;
    ProjectNormalizedToPixel(cam.model_id, cam.params.data(), c.x() / c.z(), c.y() / c.z(), &px, &py);
    if (px < 0 || py < 0 || px > cam.width_px || py > cam.height_px) continue;
    obs.push_back({id, {px + noise(rng), py + noise(rng)}});
  }
  return obs;
}

testing::SyntheticScene Scene(int model_id, std::vector<double> params) {
  testing::SyntheticOptions o;
  o.model_id = model_id;
  o.params = std::move(params);
  o.num_points = 50;
  o.enu_from_colmap = testing::DefaultColmapFrame();
  return testing::MakeSyntheticScene(o);
}

TEST(Triangulation, RecoversAPointThroughDistortedCameras) {
  struct Model {
    int id;
    std::vector<double> params;
  };
  const Model models[] = {
      {static_cast<int>(CameraModelId::kSimpleRadial), {900, 800, 450, -0.02}},
      {static_cast<int>(CameraModelId::kOpenCv), {905, 895, 801, 449, -0.05, 0.01, 0.001, -0.0005}},
      {static_cast<int>(CameraModelId::kOpenCvFisheye), {700, 700, 800, 450, 0.02, -0.01, 0.001, 0}},
  };
  for (const Model& m : models) {
    const testing::SyntheticScene scene = Scene(m.id, m.params);
    const Similarity3 colmap_from_enu = testing::DefaultColmapFrame().Inverse();
    const Eigen::Vector3d truth_enu(4.0, -3.0, 1.2);
    const Eigen::Vector3d truth = colmap_from_enu(truth_enu);
    const auto obs = Observe(scene, truth, 0.0, 1);
    ASSERT_GE(obs.size(), 4u);
    const Triangulation t = TriangulatePoint(scene.model, obs);
    ASSERT_TRUE(t.ok) << t.reason;
    // Exact pixels: the point comes back to numerical precision (COLMAP units: 1 unit = 7.5 m).
    EXPECT_LT((testing::DefaultColmapFrame()(t.xyz) - truth_enu).norm(), 1e-6) << CameraModelName(m.id);
    EXPECT_LT(t.rms_reprojection_px, 1e-6);
    EXPECT_EQ(t.num_used, static_cast<int>(obs.size()));
    EXPECT_GT(t.max_angle_deg, 10.0);
  }
}

TEST(Triangulation, NoisyPixelsGiveCentimetres) {
  const testing::SyntheticScene scene = Scene(static_cast<int>(CameraModelId::kSimpleRadial), {900, 800, 450, -0.02});
  const Eigen::Vector3d truth_enu(-10.0, 5.0, 0.5);
  const Eigen::Vector3d truth = testing::DefaultColmapFrame().Inverse()(truth_enu);
  const auto obs = Observe(scene, truth, 0.5, 3);
  const Triangulation t = TriangulatePoint(scene.model, obs);
  ASSERT_TRUE(t.ok) << t.reason;
  // 0.5 px at 40 m with f = 900 px is ~2 cm per ray.
  EXPECT_LT((testing::DefaultColmapFrame()(t.xyz) - truth_enu).norm(), 0.05);
  EXPECT_GT(t.rms_reprojection_px, 0.1);
  EXPECT_LT(t.rms_reprojection_px, 1.0);
}

TEST(Triangulation, AMisclickedObservationIsDropped) {
  const testing::SyntheticScene scene = Scene(static_cast<int>(CameraModelId::kSimpleRadial), {900, 800, 450, -0.02});
  const Eigen::Vector3d truth_enu(2.0, 1.0, 0.0);
  const Eigen::Vector3d truth = testing::DefaultColmapFrame().Inverse()(truth_enu);
  auto obs = Observe(scene, truth, 0.2, 5);
  ASSERT_GE(obs.size(), 4u);
  obs[1].pixel_px += Eigen::Vector2d(60, -40);
  const Triangulation t = TriangulatePoint(scene.model, obs);
  ASSERT_TRUE(t.ok) << t.reason;
  EXPECT_FALSE(t.observations[1].used);
  EXPECT_NE(t.observations[1].note.find("dropped"), std::string::npos) << t.observations[1].note;
  EXPECT_GT(t.observations[1].reprojection_px, 30);
  EXPECT_EQ(t.num_used, static_cast<int>(obs.size()) - 1);
  EXPECT_LT((testing::DefaultColmapFrame()(t.xyz) - truth_enu).norm(), 0.05);
}

TEST(Triangulation, TooFewOrOutsideObservationsFail) {
  const testing::SyntheticScene scene = Scene(static_cast<int>(CameraModelId::kSimpleRadial), {900, 800, 450, -0.02});
  const Eigen::Vector3d truth = testing::DefaultColmapFrame().Inverse()(Eigen::Vector3d(0, 0, 0));
  auto obs = Observe(scene, truth, 0.0, 1);
  ASSERT_GE(obs.size(), 2u);
  const Triangulation one = TriangulatePoint(scene.model, {obs[0]});
  EXPECT_FALSE(one.ok);
  EXPECT_NE(one.reason.find("fewer than 2"), std::string::npos);
  std::vector<PixelObservation> outside = {obs[0], obs[1]};
  outside[1].pixel_px = {5000, 100};  // beyond the 1600 px width: measured on the full-size original?
  const Triangulation t = TriangulatePoint(scene.model, outside);
  EXPECT_FALSE(t.ok);
  EXPECT_NE(t.observations[1].note.find("outside the image (1600 x 900 px)"), std::string::npos);
}

TEST(Triangulation, NearlyParallelRaysAreRefused) {
  // Two cameras 2 cm apart looking at a point 40 m away: 0.03 deg.
  ColmapModel model;
  model.cameras[1] = {1, static_cast<int>(CameraModelId::kPinhole), 1600, 900, {900, 900, 800, 450}};
  for (uint32_t id : {1u, 2u}) {
    ColmapImage image;
    image.image_id = id;
    image.camera_id = 1;
    image.name = "i" + std::to_string(id);
    image.cam_from_world_translation = Eigen::Vector3d(id == 1 ? 0.0 : -0.02, 0, 0);
    model.images[id] = image;
  }
  const Eigen::Vector3d x(0.5, 0.3, 40);
  std::vector<PixelObservation> obs;
  for (uint32_t id : {1u, 2u}) {
    const Eigen::Vector3d c = x + model.images[id].cam_from_world_translation;
    obs.push_back({id, {900 * c.x() / c.z() + 800, 900 * c.y() / c.z() + 450}});
  }
  const Triangulation t = TriangulatePoint(model, obs);
  EXPECT_FALSE(t.ok);
  EXPECT_NE(t.reason.find("triangulation angle"), std::string::npos) << t.reason;
  EXPECT_LT(t.max_angle_deg, 0.1);
}

}  // namespace
}  // namespace cinepath::photogrammetry
