// Points of interest read from the plan itself: stretches of samples whose camera keeps one fixed
// point centred (an ORBIT or FLYBY about a static subject). Missions then hand the pointing to the
// autopilot (MAVLink DO_SET_ROI_LOCATION, DJI towardPOI, Litchi POI) instead of listing headings and
// gimbal angles.
//
// Model: the optical axis of sample i is the ray p_i + s d_i (s > 0), d_i = world_from_camera * +z.
// For a stretch [first, last] the point of interest x is the least-squares point nearest to all its
// axes:
//   minimize  sum_i |(I − d_i d_iᵀ)(x − p_i)|²   ⇒   (sum_i (I − d_i d_iᵀ)) x = sum_i (I − d_i d_iᵀ) p_i.
// The stretch is accepted when every sample's axis passes within `max_angle_deg` of x (the angle
// between d_i and x − p_i, so x must be in front of every camera), the axes spread over more than
// twice that angle (otherwise x is not observable along the axis and a fixed heading / gimbal does
// the job) and it lasts at least `min_duration_s`. Stretches are grown greedily from the first sample,
// as long as possible, and never overlap.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/trajectory.h"

namespace cinepath::exporter {

struct RoiOptions {
  double max_angle_deg = 3.0;   // every axis passes within this angle of the point
  double min_duration_s = 2.0;  // shorter stretches are left to per-waypoint headings
};

struct RoiStretch {
  int first_sample = 0;  // indices into the samples given to DetectRoiStretches (inclusive)
  int last_sample = 0;
  Eigen::Vector3d point_enu_m = Eigen::Vector3d::Zero();
  double max_angle_deg = 0;  // largest angle between an axis and the point, over the stretch
};

// Camera optical axis (unit, ENU) of a sample.
Eigen::Vector3d OpticalAxisEnu(const TrajectorySample& sample);

// The least-squares point of samples [first, last] and its acceptance: `accepted` is false when the
// axes are (nearly) parallel or any axis misses the point by more than the tolerance.
struct RoiFit {
  bool accepted = false;
  Eigen::Vector3d point_enu_m = Eigen::Vector3d::Zero();
  double max_angle_deg = 0;
};
// require_spread = false skips the spread test (used while growing a stretch, whose short windows may
// span a small angle even on a long orbit; the whole stretch must pass it).
RoiFit FitRoi(const std::vector<TrajectorySample>& samples, int first, int last, double max_angle_deg,
              bool require_spread = true);

std::vector<RoiStretch> DetectRoiStretches(const std::vector<TrajectorySample>& samples, const RoiOptions& options);

}  // namespace cinepath::exporter
