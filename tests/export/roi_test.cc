#include "export/roi.h"

#include <gtest/gtest.h>

#include "export/mavlink_mission.h"
#include "export/mission_builder.h"
#include "sample_trajectories.h"

namespace cinepath::exporter {
namespace {

const Eigen::Vector3d kSubject(0, 0, 1.5);  // where the sample ORBIT / FLYBY look (sample_trajectories.h)

TEST(Roi, OrbitYieldsOneStretchAtTheCentre) {
  const Trajectory t = testing::OrbitPlan();
  const auto rois = DetectRoiStretches(t.samples, RoiOptions{3.0, 2.0});
  ASSERT_EQ(rois.size(), 1u);
  EXPECT_EQ(rois[0].first_sample, 0);
  EXPECT_EQ(rois[0].last_sample, static_cast<int>(t.samples.size()) - 1);
  EXPECT_LT((rois[0].point_enu_m - kSubject).norm(), 0.03);
  EXPECT_LT(rois[0].max_angle_deg, 0.01);
}

TEST(Roi, SlowOrbitYieldsOneToo) {
  // Half a turn in 60 s: any 2 s window spans only ~5 deg of axis direction, less than twice the
  // tolerance; the whole stretch spans far more (regression: such orbits used to get no ROI).
  const Trajectory t = testing::OrbitPlan(60, 30);
  const auto rois = DetectRoiStretches(t.samples, RoiOptions{3.0, 2.0});
  ASSERT_EQ(rois.size(), 1u);
  EXPECT_EQ(rois[0].first_sample, 0);
  EXPECT_EQ(rois[0].last_sample, static_cast<int>(t.samples.size()) - 1);
  EXPECT_LT((rois[0].point_enu_m - kSubject).norm(), 0.03);
}

TEST(Roi, FlybyOfAStaticSubjectYieldsOne) {
  const Trajectory t = testing::FlybyPlan();
  const auto rois = DetectRoiStretches(t.samples, RoiOptions{3.0, 2.0});
  ASSERT_EQ(rois.size(), 1u);
  EXPECT_LT((rois[0].point_enu_m - kSubject).norm(), 0.03);
}

TEST(Roi, ChaseOfAMovingSubjectYieldsNone) {
  EXPECT_TRUE(DetectRoiStretches(testing::ChasePlan().samples, RoiOptions{3.0, 2.0}).empty());
  // Not even with a loose tolerance.
  EXPECT_TRUE(DetectRoiStretches(testing::ChasePlan().samples, RoiOptions{10.0, 2.0}).empty());
}

TEST(Roi, ParallelAxesAreNotAPoint) {
  // A dolly sliding east, camera looking north all along: the axes never meet.
  Trajectory t = testing::EmptyPlan("dolly", "DOLLY", 5, 10);
  for (int i = 0; i <= 50; ++i) testing::AddSample(t, i / 10.0, Eigen::Vector3d(i * 0.5, 0, 10), 0, -10, 24, 10, 4);
  EXPECT_TRUE(DetectRoiStretches(t.samples, RoiOptions{3.0, 2.0}).empty());
}

TEST(Roi, TwoSubjectsGiveTwoStretches) {
  // Orbit one point for 5 s, then another (10 m east) for 5 s, joined continuously.
  Trajectory t = testing::EmptyPlan("two", "ORBIT", 10, 10);
  for (int i = 0; i <= 100; ++i) {
    const double time = i / 10.0;
    const Eigen::Vector3d centre = time <= 5 ? Eigen::Vector3d(0, 0, 0) : Eigen::Vector3d(10, 0, 0);
    const double angle = 0.3 * time;
    const Eigen::Vector3d p = centre + Eigen::Vector3d(20 * std::cos(angle), 20 * std::sin(angle), 20);
    const Eigen::Vector3d to = centre - p;
    testing::AddSample(t, time, p, HeadingDegFromEnuYaw(std::atan2(to.y(), to.x())),
                       DegFromRad(std::atan2(to.z(), to.head<2>().norm())), 35, to.norm(), 4);
  }
  const auto rois = DetectRoiStretches(t.samples, RoiOptions{1.0, 2.0});
  ASSERT_EQ(rois.size(), 2u);
  EXPECT_LT(rois[0].point_enu_m.norm(), 0.01);
  EXPECT_LT((rois[1].point_enu_m - Eigen::Vector3d(10, 0, 0)).norm(), 0.01);
  EXPECT_EQ(rois[0].last_sample, 50);
  EXPECT_EQ(rois[1].first_sample, 51);
}

int Count(const MavMission& m, int command) {
  int n = 0;
  for (const auto& i : m.items) n += i.command == command;
  return n;
}

Mission BuildWithRoi(const Trajectory& t, RoiTracking tracking) {
  MissionBuildOptions options;
  options.selection.roi_tracking = tracking;
  return BuildMission(t, options);
}

TEST(Roi, OrbitMissionCarriesOneRoiThenRoiNone) {
  const Trajectory t = testing::OrbitPlan();
  const Mission mission = BuildWithRoi(t, RoiTracking::kCamera);
  ASSERT_EQ(mission.rois.size(), 1u);
  EXPECT_EQ(mission.rois[0].first_waypoint, 0);
  EXPECT_EQ(mission.rois[0].last_waypoint, static_cast<int>(mission.waypoints.size()) - 1);
  // The georeferenced point is the orbit centre: back to ENU within a few cm.
  const Eigen::Vector3d enu = EnuFrame(*t.origin).EnuFromGeodetic(
      Geodetic{mission.rois[0].lat_deg, mission.rois[0].lon_deg, mission.rois[0].ellipsoidal_height_m});
  EXPECT_LT((enu - kSubject).norm(), 0.03);
  EXPECT_NEAR(mission.rois[0].relative_alt_m, 1.5, 0.03);  // home = origin

  for (Firmware firmware : {Firmware::kPx4, Firmware::kArduPilot}) {
    const MavMission m = BuildMavMission(mission, firmware, AltitudeRef::kRelative);
    EXPECT_EQ(Count(m, mav::kDoSetRoiLocation), 1);
    EXPECT_EQ(Count(m, mav::kDoSetRoiNone), 1);
    int roi_at = -1, none_at = -1;
    for (size_t i = 0; i < m.items.size(); ++i) {
      const MavItem& item = m.items[i];
      if (item.command == mav::kDoSetRoiLocation) {
        roi_at = static_cast<int>(i);
        EXPECT_EQ(item.frame, mav::kFrameGlobalRelativeAlt);
        EXPECT_NEAR(item.params[4], mission.rois[0].lat_deg, 1e-12);
        EXPECT_NEAR(item.params[5], mission.rois[0].lon_deg, 1e-12);
        EXPECT_NEAR(item.params[6], 1.5, 0.03);
      }
      if (item.command == mav::kDoSetRoiNone) {
        none_at = static_cast<int>(i);
        EXPECT_EQ(item.frame, mav::kFrameMission);
      }
      // No explicit gimbal or yaw command while the ROI is active (the ROI does both).
      if (item.command == mav::kDoGimbalManagerPitchYaw || item.command == mav::kConditionYaw) {
        EXPECT_TRUE(roi_at < 0 || none_at >= 0) << i;
      }
    }
    EXPECT_GE(roi_at, 0);
    EXPECT_GT(none_at, roi_at);
  }
}

TEST(Roi, FlybyNeedsFarFewerWaypointsWithRoi) {
  // The flyby pans fast past the subject: with explicit headings the angle tolerance forces many
  // waypoints; with the ROI the straight pass needs two.
  const Trajectory t = testing::FlybyPlan();
  const Mission without = BuildWithRoi(t, RoiTracking::kNone);
  const Mission with = BuildWithRoi(t, RoiTracking::kCamera);
  EXPECT_EQ(with.waypoints.size(), 2u);
  EXPECT_GE(without.waypoints.size(), 7u);
  EXPECT_LE(with.max_angle_error_reached_deg, 3.0);
}

TEST(Roi, HeadingTrackingOnlyWhereTheNosePointsAtThePoint) {
  // The sample orbit with the nose along the path and the gimbal panned 90 deg to the centre: the
  // camera still looks at the point (MAVLink ROI applies), but DJI's towardPOI would turn the nose —
  // and with it the camera — away, so WPML keeps explicit headings.
  Trajectory t = testing::OrbitPlan();
  for (auto& s : t.samples) {
    s.drone_heading_deg = NormalizeDeg360(s.drone_heading_deg + 90);
    s.gimbal_yaw_deg = -90;
  }
  EXPECT_EQ(BuildWithRoi(t, RoiTracking::kCamera).rois.size(), 1u);
  EXPECT_TRUE(BuildWithRoi(t, RoiTracking::kHeading).rois.empty());
  EXPECT_EQ(BuildWithRoi(testing::OrbitPlan(), RoiTracking::kHeading).rois.size(), 1u);
}

TEST(Roi, ChaseMissionHasNoRoi) {
  const Mission mission = BuildWithRoi(testing::ChasePlan(), RoiTracking::kCamera);
  EXPECT_TRUE(mission.rois.empty());
  const MavMission m = BuildMavMission(mission, Firmware::kPx4, AltitudeRef::kRelative);
  EXPECT_EQ(Count(m, mav::kDoSetRoiLocation), 0);
  EXPECT_EQ(Count(m, mav::kDoSetRoiNone), 0);
}

}  // namespace
}  // namespace cinepath::exporter
