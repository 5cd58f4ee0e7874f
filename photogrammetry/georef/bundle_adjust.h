// Bundle adjustment of a COLMAP model already moved into local ENU metres (Ceres), with priors:
//   * reprojection of every 3D point into every image of its track (robust Huber loss, pixels),
//     through the camera's own COLMAP model (camera_models.h);
//   * GPS camera centres: (C - C_gps) / sigma, horizontal and vertical sigmas in metres;
//   * focal length: (f - f_prior) / (ratio * f_prior) where a prior is given (EXIF FocalLength and the
//     sensor width, see exif_gps.h);
//   * ground control points (gcp_file.h): each is an extra point with its pixel observations
//     (reprojection residuals like any point) and a position prior (X - X_surveyed) / sigma, horizontal
//     and vertical sigmas in metres. With >= 3 of them they fix the gauge on their own (no GPS needed).
// Unknowns: each image's rotation (cam_from_enu, unit quaternion) and centre C (ENU m), each point, each
// camera's focal length(s) and distortion terms (the principal point stays fixed).
//
// Why (data/brighton_beach/README.md): a flat scene seen straight down cannot tell focal length from flying
// height. The reprojection error is (nearly) the same for f and a depth scaled with it, so the
// reconstruction drifts along that valley (COLMAP's default run of Brighton Beach grew f by 31 %, and
// a similarity fit to GPS then puts the ground 10.9 m low). The GPS priors fix the cameras' heights and
// the focal prior fixes the depth scale, which puts the ground back.
//
// Procedure, when every camera has a focal prior:
//   0. Measure the geometry as COLMAP left it: depth relief per image and the spread of the optical axes
//      (`min_depth_relief_ratio`, `min_view_axis_spread_deg`). Below both, the views cannot separate
//      focal length from depth (a near-planar scene under near-parallel views: the nadir survey).
//   1. Where the geometry resolves it (a facade with relief seen from the ground, an oblique orbit), the
//      focal length the photos measure: solve with it free from COLMAP's value and the prior as a weak
//      pull (`measured_focal_prior_sigma_ratio`: an EXIF 35 mm equivalent is rounded by the camera, so it
//      is a few per cent off), then profile it (step 3). Kept when the profile confirms that the images
//      determine it (sigma below `resolvable_sigma_ratio`); otherwise steps 2-4 run from the start.
//   2. Start at the prior focal length with the points moved along the focal/depth valley (each depth
//      scaled by f_prior / f), and solve with the focal length held at the prior.
//   3. Profile: move the focal length by ±profile_step (points moved along the valley again), hold it,
//      re-solve; the reprojection cost's curvature over the three solutions gives the focal length's
//      standard deviation from the images alone (sigma_f = sigma_px / sqrt(d²cost/df²)) and the focal
//      they prefer (the parabola's minimum).
//   4. Only with free_focal_when_resolved, and when the images resolve it (sigma below
//      `resolvable_sigma_ratio`) AND agree with the prior (preferred focal within
//      `max_focal_disagreement_ratio`) is the focal length freed (with its prior) and solved again.
//      Otherwise it stays at the prior, and the report says why. (On Brighton Beach the images "prefer"
//      +24 % with a formal sigma of 0.7 %: a systematic pull along the valley that the independent
//      OpenDroneMap reference shows to be wrong; its geometry does not pass step 0.)
// Without priors the focal length is free from the start and the profile only reports.
//
// Deterministic: one thread, fixed iteration order (ordered maps). CINEPATH_BA_VERBOSE=1 in the
// environment prints each solve (iterations, time, cost) to stderr.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "photogrammetry/georef/triangulation.h"
#include "photogrammetry/io/colmap_model.h"

namespace cinepath::photogrammetry {

struct BundleAdjustOptions {
  double reprojection_huber_px = 1.0;
  double gps_sigma_horizontal_m = 3.0;
  double gps_sigma_vertical_m = 3.0;
  double focal_prior_sigma_ratio = 0.01;
  bool refine_focal = true;
  bool refine_distortion = true;
  int max_iterations = 100;
  double profile_step_ratio = 0.05;  // focal moved by ±5 % for the resolvability profile
  double resolvable_sigma_ratio = 0.02;
  // The images "conflict" with the prior when the focal length they prefer is further than this from it;
  // the focal length then stays at the prior.
  double max_focal_disagreement_ratio = 0.05;
  int profile_iterations = 15;
  // Geometry that can separate focal length from depth: enough depth relief in the views (RMS depth
  // spread / median depth, per image, median over images) or enough spread of viewing directions
  // (largest angle between an optical axis and their mean). Below both, the images cannot resolve it
  // whatever the statistics say (a near-planar scene under near-parallel views is exactly ambiguous).
  double min_depth_relief_ratio = 0.15;
  double min_view_axis_spread_deg = 20.0;
  // Step 1: keep the focal length the photos measure where the geometry resolves it, with the prior at
  // this relative sigma (a weak pull: EXIF 35 mm equivalents are rounded, 5 % off is common).
  bool keep_measured_focal = true;
  double measured_focal_prior_sigma_ratio = 0.10;
  // Step 4 below is off by default: on Brighton Beach freeing the focal length (prior sigma 1 %) lets the
  // GPS heights pull it to +2.2 % and the ground 0.9 m lower, although the images agree with the prior.
  bool free_focal_when_resolved = false;
  bool profile_focal = true;
};

// A ground control point for the adjustment: observations (COLMAP pixel convention), a start position
// and the surveyed position, both in ENU metres.
struct ControlPointPrior {
  std::vector<PixelObservation> observations;  // (image id, pixel in the COLMAP convention)
  Eigen::Vector3d initial_enu_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d target_enu_m = Eigen::Vector3d::Zero();
  double sigma_horizontal_m = 0.05;
  double sigma_vertical_m = 0.05;
};

struct FocalReport {
  uint32_t camera_id = 0;
  double before_px = 0;  // mean of fx, fy
  double after_px = 0;
  std::optional<double> prior_px;
  // From the profile: the focal's standard deviation from the images alone (relative), and the focal the
  // images alone prefer (parabola minimum); unset when the profile was not run or is degenerate.
  std::optional<double> images_sigma_ratio;
  std::optional<double> images_preferred_px;
  bool images_resolve_focal = false;
  bool images_conflict_with_prior = false;
  bool held_at_prior = false;       // the focal length was fixed at the prior
  bool measured_by_images = false;  // step 1: the focal length the photos measure was kept
};

struct BundleAdjustReport {
  double depth_relief_ratio = 0;    // see BundleAdjustOptions::min_depth_relief_ratio
  double view_axis_spread_deg = 0;  // see BundleAdjustOptions::min_view_axis_spread_deg
  bool geometry_resolves_focal = false;
  int num_images = 0;
  int num_points = 0;
  int num_observations = 0;
  int num_gps_priors = 0;
  int num_control_points = 0;
  int iterations = 0;
  bool converged = false;
  double rms_reprojection_before_px = 0;
  double rms_reprojection_after_px = 0;
  std::vector<FocalReport> focal;
  double time_s = 0;
};

// Adjusts `model_enu` in place (poses, points, intrinsics). `gps_enu_m` maps image ids to their
// reference centres in ENU; `focal_prior_px` maps camera ids to prior focal lengths. Control points
// (optional) join the problem; their adjusted positions go to `control_points_enu_m` when given.
// InfeasibleError when the problem has no observations.
BundleAdjustReport BundleAdjustEnu(ColmapModel& model_enu, const std::map<uint32_t, Eigen::Vector3d>& gps_enu_m,
                                   const std::map<uint32_t, double>& focal_prior_px, const BundleAdjustOptions& options,
                                   const std::vector<ControlPointPrior>& control_points = {},
                                   std::vector<Eigen::Vector3d>* control_points_enu_m = nullptr);

// RMS reprojection error over every track observation (pixels), through each camera's model.
double RmsReprojectionErrorPx(const ColmapModel& model);

}  // namespace cinepath::photogrammetry
