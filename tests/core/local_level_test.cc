#include "core/local_level.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>

#include <gtest/gtest.h>

#include "core/angles.h"

namespace cinepath {
namespace {

// Where `target` lies seen from `from` (both geodetic), in the local ENU frame at `from`, by
// GeographicLib's own CartConvert (Debian geographiclib-tools): the oracle for a heading and a pitch.
bool CartConvertLocal(const Geodetic& from, const Geodetic& target, Eigen::Vector3d* local_m) {
  char cmd[320];
  std::snprintf(cmd, sizeof cmd, "echo '%.12f %.12f %.6f' | CartConvert -p 9 -l %.12f %.12f %.6f", target.lat_deg,
                target.lon_deg, target.height_m, from.lat_deg, from.lon_deg, from.height_m);
  FILE* pipe = popen(cmd, "r");
  if (!pipe) return false;
  const int read = std::fscanf(pipe, "%lf %lf %lf", &local_m->x(), &local_m->y(), &local_m->z());
  pclose(pipe);
  return read == 3;
}

double HeadingDeg(const Eigen::Vector3d& v) { return NormalizeDeg360(DegFromRad(std::atan2(v.x(), v.y()))); }
double PitchDeg(const Eigen::Vector3d& v) { return DegFromRad(std::atan2(v.z(), v.head<2>().norm())); }

TEST(LocalLevel, TheIdentityAtTheOrigin) {
  for (const Geodetic origin : {Geodetic{46.84, -91.99, 150}, Geodetic{89.95, 135, 2800}, Geodetic{-90, 45, 0}}) {
    const EnuFrame frame(origin);
    EXPECT_LT((frame.LocalLevelFromEnu(Eigen::Vector3d::Zero()) - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  }
}

// A camera aimed from a drone at a subject: its heading and pitch where it flies are the subject's
// bearing and elevation there, as CartConvert finds them. Near the pole the frame's north is 1.3 deg
// off true north 1.5 km from the origin (a 1,200 mm lens sees 1.7 deg across); 10 km east at 47 deg
// the convergence is 0.12 deg and the vertical tilts by 0.09 deg.
TEST(LocalLevel, HeadingAndPitchAreTheSubjectsBearingAndElevationWhereTheDroneIs) {
  if (std::system("command -v CartConvert > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "CartConvert (geographiclib-tools) not installed";
  }
  struct Case {
    Geodetic origin;
    Eigen::Vector3d drone_enu_m, subject_enu_m;
    double frame_heading_off_deg;  // at least this far off with the scene frame's axes
  };
  const Case cases[] = {
      {{89.95, 135, 2800}, {-165, -1500, 60}, {-150, 0, 0}, 1.0},
      {{46.842583, -91.993884, 161.94}, {10000, 200, 120}, {9990, 260, 0}, 0.05},
      {{-89.99, -10, 0}, {300, 400, 30}, {0, 0, 2}, 1.0},
  };
  for (const Case& c : cases) {
    const EnuFrame frame(c.origin);
    const Eigen::Quaterniond q = LookAt(c.subject_enu_m - c.drone_enu_m);
    Eigen::Vector3d seen;
    ASSERT_TRUE(CartConvertLocal(frame.GeodeticFromEnu(c.drone_enu_m), frame.GeodeticFromEnu(c.subject_enu_m), &seen));
    const GimbalAngles local = LocalGimbalAngles(&frame, c.drone_enu_m, q);
    EXPECT_NEAR(AngleDiffDeg(HeadingDeg(seen), local.drone_heading_deg), 0.0, 1e-6) << c.origin.lat_deg;
    EXPECT_NEAR(local.gimbal_pitch_deg, PitchDeg(seen), 1e-6) << c.origin.lat_deg;
    EXPECT_NEAR(local.gimbal_yaw_deg, 0.0, 1e-12);
    // Aimed level where the drone is, the horizon is level there.
    const Eigen::Matrix3d local_from_enu = frame.LocalLevelFromEnu(c.drone_enu_m);
    const Eigen::Quaterniond level(local_from_enu.transpose() *
                                   LookAt(local_from_enu * (c.subject_enu_m - c.drone_enu_m)));
    EXPECT_NEAR(LocalGimbalAngles(&frame, c.drone_enu_m, level).gimbal_roll_deg, 0.0, 1e-9);
    // The scene frame's axes are not the drone's: the test can tell them apart.
    const GimbalAngles grid = LocalGimbalAngles(nullptr, c.drone_enu_m, q);
    EXPECT_GT(std::abs(AngleDiffDeg(HeadingDeg(seen), grid.drone_heading_deg)), c.frame_heading_off_deg);
  }
}

TEST(LocalLevel, AnglesRoundTripWhereverTheCameraIs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const Geodetic origin : {Geodetic{60, 10, 0}, Geodetic{89.99, -170, 500}, Geodetic{-33.9, 151.2, 40}}) {
    const EnuFrame frame(origin);
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector3d position(5000 * unit(rng), 5000 * unit(rng), 300 * unit(rng));
      GimbalAngles g;
      g.drone_heading_deg = NormalizeDeg360(180 * unit(rng));
      g.gimbal_pitch_deg = 85 * unit(rng);
      g.gimbal_roll_deg = 30 * unit(rng);
      const Eigen::Quaterniond q = LocalWorldFromCamera(&frame, position, g);
      EXPECT_GE(q.w(), 0.0);
      const GimbalAngles back = LocalGimbalAngles(&frame, position, q);
      EXPECT_NEAR(AngleDiffDeg(g.drone_heading_deg, back.drone_heading_deg), 0.0, 1e-9);
      EXPECT_NEAR(back.gimbal_pitch_deg, g.gimbal_pitch_deg, 1e-9);
      EXPECT_NEAR(back.gimbal_roll_deg, g.gimbal_roll_deg, 1e-9);
      // A nose off the camera keeps its heading; the gimbal yaw takes up the rest.
      const GimbalAngles nose = LocalGimbalAngles(&frame, position, q, g.drone_heading_deg + 20);
      EXPECT_NEAR(nose.gimbal_yaw_deg, -20.0, 1e-9);
    }
  }
}

TEST(LocalLevel, WithoutAFrameTheSceneAxes) {
  const Eigen::Quaterniond q = LookAt({1, 1, -0.5});
  TrajectorySample s;
  s.position_enu_m = {1000, -2000, 50};
  s.world_from_camera = q;
  SetLocalAngles(nullptr, s);
  const GimbalAngles plain = GimbalFromWorldFromCamera(q);
  EXPECT_EQ(s.drone_heading_deg, plain.drone_heading_deg);
  EXPECT_EQ(s.gimbal_pitch_deg, plain.gimbal_pitch_deg);
  EXPECT_EQ(LocalWorldFromCamera(nullptr, s.position_enu_m, plain).coeffs(), WorldFromCameraFromGimbal(plain).coeffs());
}

}  // namespace
}  // namespace cinepath
