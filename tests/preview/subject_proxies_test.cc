#include "preview/subject_proxies.h"

#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

namespace cinepath::preview {
namespace {

// A deterministic uniform draw in [-1, 1).
class Draw {
 public:
  explicit Draw(uint32_t seed) : state_(seed) {}
  double operator()() {
    state_ = state_ * 1664525u + 1013904223u;
    return double(state_ >> 8) / double(1 << 24) * 2 - 1;
  }

 private:
  uint32_t state_;
};

Trajectory TwoSubjects() {
  Trajectory plan;
  plan.samples.resize(1);
  plan.subjects.resize(2);
  plan.subjects[0].height_m = 1.8;
  plan.subjects[1].height_m = 1.75;
  return plan;
}

// Culling must never drop a hit: wherever InImage says a pinhole ray cannot meet a proxy, Intersect finds
// none, for subjects in front of the camera, beside it, behind it, across its plane and at its centre,
// through every pixel centre and points between them.
TEST(SubjectsInImage, NeverHidesAProxyThatAPinholeRayHits) {
  const Trajectory plan = TwoSubjects();
  const SubjectProxies proxies(plan);
  CameraSpec spec;
  Draw draw(11);
  int culled = 0, tested = 0, hits = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int w = 96, h = 54;
    const ThinLensCamera camera(spec, w, h, trial % 3 == 0 ? 12 : trial % 3 == 1 ? 50 : 400, 2.8, 10);
    const CameraPose pose{Eigen::Vector3d(draw(), draw(), draw()) * 5,
                          Eigen::Quaterniond(draw(), draw(), draw(), draw()).normalized()};
    const CameraFrame frame(pose);
    // Subjects where the camera looks (most trials), anywhere near it, or straddling its centre.
    std::vector<Eigen::Vector3d> bases(2);
    const Eigen::Vector3d axis = frame.world_from_camera.col(2);
    for (size_t i = 0; i < bases.size(); ++i) {
      const double kind = draw();
      bases[i] = kind < 0     ? Eigen::Vector3d(pose.position_enu_m + axis * (3 + 40 * std::abs(draw())) +
                                                Eigen::Vector3d(draw(), draw(), draw()) * 3)
                 : kind < 0.7 ? Eigen::Vector3d(pose.position_enu_m + Eigen::Vector3d(draw(), draw(), draw()) * 20)
                              : Eigen::Vector3d(pose.position_enu_m + Eigen::Vector3d(0.1 * draw(), 0.1 * draw(), -1));
    }
    const SubjectsInImage seen = proxies.InImage(bases, camera, frame);
    for (int y = 0; y < 2 * h; ++y) {
      for (int x = 0; x < 2 * w; ++x) {
        const double x_px = 0.5 * x + 0.25, y_px = 0.5 * y + 0.25;
        const CameraRay ray = camera.Ray(frame, x_px, y_px);
        const bool hit = proxies.Intersect(ray.origin_enu_m, ray.direction_enu, bases, 1e9).has_value();
        ++tested;
        hits += hit;
        if (!seen.MaySee(x_px, y_px)) {
          ++culled;
          ASSERT_FALSE(hit) << "trial " << trial << " at (" << x_px << ", " << y_px << ")";
        }
      }
    }
  }
  // It culls: most rays of these frames miss both subjects and are known to.
  EXPECT_GT(hits, 1000);
  EXPECT_GT(culled, tested / 2);
}

// A subject straight ahead is seen only around where it stands in the image; one behind the camera
// nowhere.
TEST(SubjectsInImage, BoundsASubjectAheadAndDropsOneBehind) {
  const Trajectory plan = TwoSubjects();
  const SubjectProxies proxies(plan);
  CameraSpec spec;
  const ThinLensCamera camera(spec, 640, 360, 50, 2.8, 10);
  Eigen::Matrix3d r;  // looking north, level: camera x east, y down, z north
  r << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  const CameraFrame frame(CameraPose{Eigen::Vector3d(0, 0, 1.5), Eigen::Quaterniond(r)});
  const std::vector<Eigen::Vector3d> bases = {Eigen::Vector3d(0, 20, 0), Eigen::Vector3d(0, -20, 0)};
  const SubjectsInImage seen = proxies.InImage(bases, camera, frame);
  double depth = 0;
  const Eigen::Vector2d middle = camera.Project(frame, Eigen::Vector3d(0, 20, 0.9), &depth);
  EXPECT_TRUE(seen.MaySee(middle.x(), middle.y()));
  EXPECT_FALSE(seen.MaySee(5, 5));
  EXPECT_FALSE(seen.MaySee(635, 355));
  EXPECT_FALSE(seen.MaySee(middle.x() + 100, middle.y()));
  EXPECT_TRUE(SubjectsInImage::Everywhere().MaySee(5, 5));
}

}  // namespace
}  // namespace cinepath::preview
