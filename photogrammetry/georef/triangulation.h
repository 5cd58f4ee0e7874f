// Triangulating a point from its pixel observations in registered images of a COLMAP model (for
// ground control points, gcp_file.h).
//
// Each observation is undistorted through the image's camera model (camera_models.h
// PixelToNormalized) into a ray from the camera centre C along d = R^T (u, v, 1) (world frame of the
// model). The point:
//   1. linear: the least-squares point nearest to every ray, X = argmin sum |(I - d d^T)(X - C)|^2;
//   2. refined by minimizing the pixel reprojection error through each camera's full model (Ceres,
//      3 unknowns, a few iterations);
//   3. when an observation's reprojection error exceeds `max_reprojection_px` and more than two remain,
//      the worst is dropped (a mis-clicked pixel) and the point re-triangulated.
// The triangulation angle reported is the largest angle between two rays that were used: a point
// seen under near-parallel rays has an unreliable depth (COLMAP's mapper wants >= 1.5 deg).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "photogrammetry/io/colmap_model.h"

namespace cinepath::photogrammetry {

struct PixelObservation {
  uint32_t image_id = 0;
  Eigen::Vector2d pixel_px = Eigen::Vector2d::Zero();  // COLMAP convention
};

struct TriangulationOptions {
  double max_reprojection_px = 4.0;
  double min_angle_deg = 1.0;
};

struct ObservationResult {
  bool used = false;
  double reprojection_px = -1;  // through the final point; -1 when the point is not in front
  std::string note;             // why it was not used ("outside the image", "reprojection 9.1 px", ...)
};

struct Triangulation {
  bool ok = false;
  std::string reason;                             // why not ok
  Eigen::Vector3d xyz = Eigen::Vector3d::Zero();  // model frame
  std::vector<ObservationResult> observations;    // one per input observation
  int num_used = 0;
  double rms_reprojection_px = 0;  // over the used observations
  double max_angle_deg = 0;
};

// Never throws for bad geometry: the result says why it failed. Image ids must exist in `model`.
Triangulation TriangulatePoint(const ColmapModel& model, const std::vector<PixelObservation>& observations,
                               const TriangulationOptions& options = {});

}  // namespace cinepath::photogrammetry
