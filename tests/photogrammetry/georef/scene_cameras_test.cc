// photogrammetry/georef/scene_cameras.h: a photo's pose and camera as scene.json records them.
#include "photogrammetry/georef/scene_cameras.h"

#include <gtest/gtest.h>

#include "photogrammetry/georef/camera_models.h"

namespace cinepath::photogrammetry {
namespace {

TEST(SceneCameras, PoseIsTheInverseOfColmapsAndTheCameraIsSplitIntoPinholeAndDistortion) {
  ColmapModel model;
  ColmapCamera radial;
  radial.camera_id = 7;
  radial.model_id = int(CameraModelId::kSimpleRadial);
  radial.width_px = 1600;
  radial.height_px = 1200;
  radial.params = {914.4, 800.5, 600.25, -0.012};
  model.cameras[7] = radial;
  ColmapCamera pinhole;
  pinhole.camera_id = 8;
  pinhole.model_id = int(CameraModelId::kPinhole);
  pinhole.width_px = 640;
  pinhole.height_px = 480;
  pinhole.params = {500, 510, 320, 240};
  model.cameras[8] = pinhole;
  // A camera 10 m up looking straight down, its image top to the north: camera x = east, y = south,
  // z = down in ENU.
  ColmapImage down;
  down.image_id = 2;
  down.camera_id = 7;
  down.name = "DJI_0018.JPG";
  Eigen::Matrix3d world_from_camera;
  world_from_camera.col(0) = Eigen::Vector3d(1, 0, 0);
  world_from_camera.col(1) = Eigen::Vector3d(0, -1, 0);
  world_from_camera.col(2) = Eigen::Vector3d(0, 0, -1);
  const Eigen::Vector3d centre(3, 4, 10);
  down.cam_from_world_rotation = Eigen::Quaterniond(world_from_camera.transpose());
  down.cam_from_world_translation = -(world_from_camera.transpose() * centre);
  model.images[2] = down;
  ColmapImage other = down;
  other.image_id = 1;
  other.camera_id = 8;
  other.name = "first.jpg";
  model.images[1] = other;

  const Json cameras = SceneCamerasJson(model);
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_EQ(cameras[0]["image"], "first.jpg");  // image-id order
  const Json& c = cameras[1];
  EXPECT_EQ(c["image"], "DJI_0018.JPG");
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(c["position_enu_m"][i].get<double>(), centre[i], 1e-6);
  const Eigen::Quaterniond q(c["world_from_camera"][0].get<double>(), c["world_from_camera"][1].get<double>(),
                             c["world_from_camera"][2].get<double>(), c["world_from_camera"][3].get<double>());
  EXPECT_LT((q.toRotationMatrix() - world_from_camera).norm(), 1e-8);
  EXPECT_GE(q.w(), 0.0);
  EXPECT_EQ(c["focal_px"], 914.4);
  EXPECT_FALSE(c.contains("focal_y_px"));
  EXPECT_EQ(c["principal_point_px"], Json::array({800.5, 600.25}));
  EXPECT_EQ(c["width_px"], 1600);
  EXPECT_EQ(c["height_px"], 1200);
  EXPECT_EQ(c["distortion"]["model"], "SIMPLE_RADIAL");
  EXPECT_EQ(c["distortion"]["params"], Json::array({-0.012}));
  EXPECT_EQ(cameras[0]["focal_y_px"], 510.0);
  EXPECT_EQ(cameras[0]["distortion"]["params"].size(), 0u);
}

}  // namespace
}  // namespace cinepath::photogrammetry
