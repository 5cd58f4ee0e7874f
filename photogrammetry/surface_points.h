// Point selection before surface reconstruction: drop the points a surface should not pass through —
// large reprojection error, short tracks (seen by too few cameras), non-finite positions.
#pragma once

#include <cstdint>

#include "core/json.h"
#include "photogrammetry/point_cloud.h"

namespace cinepath::photogrammetry {

struct PointFilterOptions {
  double max_reprojection_error_px = 2.0;  // points with a larger COLMAP ERROR are dropped
  int min_track_length = 3;                // points seen by fewer cameras are dropped
};

struct PointFilterReport {
  int64_t points_in = 0, points_out = 0;
  int64_t removed_non_finite = 0, removed_reprojection = 0, removed_short_track = 0;
  Json ToJson() const;
};

// Keeps every per-point attribute that is present (colours, normals, errors, observers) aligned
// with the kept points, and keeps camera_centers_m as is. Criteria whose data is absent (no errors,
// no observers) are skipped.
PointCloud FilterPoints(const PointCloud& cloud, const PointFilterOptions& options, PointFilterReport* report);

// True when the cameras look down on the points (nadir / oblique-down capture, see the .cc).
// Without cameras, true when the cloud is much wider than it is tall.
bool LooksLikeNadirCapture(const PointCloud& cloud);

}  // namespace cinepath::photogrammetry
