// Synthetic per-frame plans for the export tests, goldens and benchmarks: ORBIT, CHASE and FLYBY
// shots about a subject at the ENU origin (Zurich, the PX4 SITL home), built in code.
#pragma once

#include <cmath>
#include <string>

#include "core/angles.h"
#include "core/geodesy.h"
#include "core/trajectory.h"

namespace cinepath::exporter::testing {

inline Geodetic SampleOrigin() { return Geodetic{47.3977419, 8.545594, 535.3}; }

inline Trajectory EmptyPlan(const std::string& shot, const std::string& type, double duration_s, double rate_hz) {
  Trajectory t;
  t.origin = SampleOrigin();
  t.frame_rate_hz = rate_hz;
  t.camera.min_focal_length_mm = 24;
  t.camera.max_focal_length_mm = 70;
  t.drone.name = "sample";
  t.drone.max_horizontal_speed_m_s = 15;
  t.drone.min_altitude_m = 1;
  t.drone.max_altitude_m = 120;
  t.shots.push_back(ShotSpan{shot, type, 0, duration_s, "actor", "continuous"});
  return t;
}

inline void AddSample(Trajectory& t, double time_s, const Eigen::Vector3d& p, double heading_deg, double pitch_deg,
                      double focal_mm, double focus_m, double f_number) {
  TrajectorySample s;
  s.time_s = time_s;
  s.position_enu_m = p;
  if (t.origin) s.geodetic = EnuFrame(*t.origin).GeodeticFromEnu(p);
  // Camera looks along the heading, tilted by the gimbal pitch (camera z forward, y down).
  const double yaw_enu = EnuYawFromHeadingDeg(heading_deg);
  const Eigen::Vector3d forward(std::cos(yaw_enu) * std::cos(RadFromDeg(pitch_deg)),
                                std::sin(yaw_enu) * std::cos(RadFromDeg(pitch_deg)), std::sin(RadFromDeg(pitch_deg)));
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d world_from_camera;
  world_from_camera.col(0) = right;
  world_from_camera.col(1) = down;
  world_from_camera.col(2) = forward;
  s.world_from_camera = Eigen::Quaterniond(world_from_camera).normalized();
  s.drone_heading_deg = NormalizeDeg360(heading_deg);
  s.gimbal_pitch_deg = pitch_deg;
  s.focal_length_mm = focal_mm;
  s.focus_distance_m = focus_m;
  s.f_number = f_number;
  s.shot = t.shots.front().name;
  t.samples.push_back(s);
}

// Circle of radius 30 m at 25 m about the subject, looking at it, 10 s, half a turn.
inline Trajectory OrbitPlan(double duration_s = 10, double rate_hz = 30) {
  Trajectory t = EmptyPlan("orbit", "ORBIT", duration_s, rate_hz);
  const double radius = 30, up = 25;
  const int n = static_cast<int>(std::round(duration_s * rate_hz)) + 1;
  for (int i = 0; i < n; ++i) {
    const double time = i / rate_hz;
    const double angle = kPi * time / duration_s;  // half a turn
    const Eigen::Vector3d p(radius * std::cos(angle), radius * std::sin(angle), up);
    const double heading = HeadingDegFromEnuYaw(std::atan2(-p.y(), -p.x()));
    const double pitch = -DegFromRad(std::atan2(up - 1.5, radius));
    AddSample(t, time, p, heading, pitch, 35, std::hypot(radius, up - 1.5), 4);
  }
  return t;
}

// Follows a subject running north, accelerating, zooming in from 24 to 50 mm, 8 s.
inline Trajectory ChasePlan(double duration_s = 8, double rate_hz = 30) {
  Trajectory t = EmptyPlan("chase", "CHASE", duration_s, rate_hz);
  const int n = static_cast<int>(std::round(duration_s * rate_hz)) + 1;
  for (int i = 0; i < n; ++i) {
    const double time = i / rate_hz;
    const double north = 2.0 * time + 0.4 * time * time;  // 2 m/s → 8.4 m/s
    const double east = 6.0 * std::sin(time * 0.5);       // gentle weave
    const Eigen::Vector3d p(east - 5, north - 12, 8 + 0.5 * time);
    const double heading = NormalizeDeg360(DegFromRad(std::atan2(3.0 * std::cos(time * 0.5), 2.0 + 0.8 * time)));
    AddSample(t, time, p, heading, -12 + 0.5 * time, 24 + 26 * time / duration_s, 12, 2.8 + 0.2 * time);
  }
  return t;
}

// Passes the subject at 15 m, panning to keep it framed, focus following, 12 s.
inline Trajectory FlybyPlan(double duration_s = 12, double rate_hz = 30) {
  Trajectory t = EmptyPlan("flyby", "FLYBY", duration_s, rate_hz);
  const int n = static_cast<int>(std::round(duration_s * rate_hz)) + 1;
  for (int i = 0; i < n; ++i) {
    const double time = i / rate_hz;
    const Eigen::Vector3d p(-60 + 10 * time, 15, 20 - 0.5 * time);
    const Eigen::Vector3d to_subject = Eigen::Vector3d(0, 0, 1.5) - p;
    const double heading = HeadingDegFromEnuYaw(std::atan2(to_subject.y(), to_subject.x()));
    const double pitch = DegFromRad(std::atan2(to_subject.z(), to_subject.head<2>().norm()));
    const double focus = time > 11 ? INFINITY : to_subject.norm();
    AddSample(t, time, p, heading, pitch, 50, focus, 5.6);
  }
  return t;
}

}  // namespace cinepath::exporter::testing
