#include "export/camera_track.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

TEST(CameraTrack, FramesFromTimesAndTheSignOfTheQuaternionKept) {
  const Trajectory plan = testing::OrbitPlan(2, 30);
  const CameraTrack track = TrackOfFlight(plan, "north", "plan.json", false);
  ASSERT_EQ(track.keys.size(), plan.samples.size());
  for (size_t i = 0; i < track.keys.size(); ++i) {
    EXPECT_EQ(track.keys[i].frame, static_cast<long>(i));
    if (i > 0) EXPECT_GE(track.keys[i].yup_from_camera.dot(track.keys[i - 1].yup_from_camera), 0);
  }
}

TEST(CameraTrack, ASampleOffTheFrameGridIsRefusedNamingIt) {
  Trajectory plan = testing::OrbitPlan(1, 10);
  plan.samples[3].time_s += 0.04;  // 0.4 of a frame
  try {
    TrackOfFlight(plan, "north", "plan.json", true);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("plan.json: flights[north].samples[3].time_s"), std::string::npos) << e.what();
  }
  plan.samples.clear();
  EXPECT_THROW(TrackOfFlight(plan, "north", "plan.json", false), InputError);
}

}  // namespace
}  // namespace cinepath::exporter
