// Choosing as few waypoints as possible from a per-frame trajectory such that what the autopilot flies
// between them stays close to the plan.
//
// Model of the flown path: straight legs between consecutive waypoints; along a leg, heading, gimbal
// pitch and gimbal yaw change linearly with the distance flown (DJI smoothTransition /
// gimbalEvenlyRotate; the shortest way round for angles). For every plan sample between two waypoints
// the exact error is measured: the distance from the sample to the leg (point-to-segment) and the
// difference between the sample's angles and the interpolated ones at the sample's projection on the
// leg. Greedy: from each waypoint the leg is extended sample by sample while both errors stay within
// the tolerances; the last sample always becomes a waypoint.
#pragma once

#include <vector>

#include "core/trajectory.h"
#include "export/roi.h"

namespace cinepath::exporter {

// How the autopilot points the camera on a leg inside a point-of-interest stretch (roi.h):
//   kNone    no ROI: heading and gimbal interpolated linearly (the model above);
//   kCamera  the camera itself tracks the point (MAVLink DO_SET_ROI_LOCATION, Litchi POI with gimbal
//            mode "focus POI"): the error is the angle between the plan's optical axis and the
//            direction from the flown point to the ROI;
//   kHeading the nose tracks the point horizontally, the gimbal is interpolated (DJI WPML towardPOI):
//            heading error against the bearing from the flown point to the ROI, gimbal pitch and yaw
//            linear as in kNone.
enum class RoiTracking { kNone, kCamera, kHeading };

struct SelectionOptions {
  double max_deviation_m = 0.5;  // largest allowed distance between the flown leg and the plan
  double max_angle_deg = 3.0;    // largest allowed heading / gimbal error
  RoiTracking roi_tracking = RoiTracking::kNone;
  // Point-of-interest stretches (sample indices of the samples given to SelectWaypoints). Their first
  // and last samples always become waypoints; legs inside a stretch are measured with roi_tracking.
  std::vector<RoiStretch> rois;
  void Check() const;  // InputError for non-positive or non-finite tolerances
};

struct Selection {
  std::vector<int> sample_indices;  // increasing; first = 0, last = samples.size() − 1
  double max_deviation_m = 0;       // largest deviation actually reached
  double max_angle_error_deg = 0;   // largest angle error actually reached
};

// Error of the leg a→b for the samples strictly between them.
struct LegError {
  double deviation_m = 0;
  double angle_deg = 0;
};
LegError MeasureLeg(const std::vector<TrajectorySample>& samples, int a, int b);
// The same with the leg inside a point-of-interest stretch (roi may be null: linear model).
LegError MeasureLeg(const std::vector<TrajectorySample>& samples, int a, int b, const RoiStretch* roi,
                    RoiTracking tracking);

// Requires at least one sample; a single sample yields a single waypoint.
Selection SelectWaypoints(const std::vector<TrajectorySample>& samples, const SelectionOptions& options);

}  // namespace cinepath::exporter
