// How finely each point of the surface is seen by a plan's cameras: for `cinepath mesh --for-plan`
// (mesh_decimate_for_plan.h, docs/mesh.md "Detail where the cameras look").
//
// Every sample (frame) of plan.json is a pinhole camera: its pose (position_enu_m, world_from_camera:
// x right, y down, z forward), its focal length in pixels (focal_length_mm × width_px / the width of
// the image on the sensor, core/optics.h sensor fit) and its image (width_px × height_px, principal point
// at the centre). A point is seen by a frame when it lies in the frame's frustum: in front of the camera
// and projecting inside the image. There is no occlusion test: a point hidden behind a wall still counts
// as seen, which only ever asks for more detail, never less.
//
// A displacement of e metres at a point p seen by a camera moves its image by at most
//   e · focal_px · |p − c| / z²            (z the depth along the optical axis, c the camera centre)
// to first order: the largest singular value of the projection's Jacobian. On the optical axis that is
// e · focal_px / z, the usual "distance / depth × focal"; off axis it is larger by 1/cos(angle off axis).
// metres_per_px = z² / (focal_px · |p − c|) is therefore the largest error that stays under one pixel,
// and the finest camera (the smallest metres_per_px over every frame that sees the point: the closest
// one for a fixed lens) sets the budget.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/trajectory.h"

namespace cinepath::photogrammetry {

struct PlanCamera {
  int sample_index = 0;  // the frame in plan.json's samples
  std::string drone;     // whose samples, in a plan of several drones (empty for one)
  double time_s = 0;
  Eigen::Vector3d center_enu_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d camera_from_world = Eigen::Matrix3d::Identity();  // rows: camera x, y, z in ENU
  double focal_px = 1;
  double width_px = 1, height_px = 1;  // principal point at the centre
};

// One camera per plan sample, in sample order. InputError naming `source` when the plan has no sample.
std::vector<PlanCamera> CamerasFromPlan(const Trajectory& plan, const std::string& source);

// The finest view of a point over every camera that sees it.
struct PointView {
  double metres_per_px = std::numeric_limits<double>::infinity();  // +inf: no camera sees the point
  int camera = -1;                                                 // index into the cameras; -1: unseen
  double depth_m = 0;                                              // the point's depth in that camera
  bool seen() const { return camera >= 0; }
};

// The finest view of one point (ties go to the lowest camera index).
PointView FinestView(const Eigen::Vector3d& point_enu_m, const std::vector<PlanCamera>& cameras);

// FinestView for many points, in parallel over fixed chunks (the same result at any thread count).
std::vector<PointView> FinestViews(const std::vector<Eigen::Vector3d>& points_enu_m,
                                   const std::vector<PlanCamera>& cameras);

}  // namespace cinepath::photogrammetry
