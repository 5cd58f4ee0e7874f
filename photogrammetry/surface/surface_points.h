// Point selection before surface reconstruction: drop the points a surface should not pass through —
// non-finite positions, large reprojection error, short tracks (seen by too few cameras), then, among
// the rest, isolated points (far from their neighbours compared with how far those neighbours are
// from theirs) and points off the local surface (far from a robust plane fitted to their neighbours).
#pragma once

#include <cstdint>

#include "core/json.h"
#include "photogrammetry/io/point_cloud.h"

namespace cinepath::photogrammetry {

struct PointFilterOptions {
  double max_reprojection_error_px = 2.0;  // points with a larger COLMAP ERROR are dropped
  int min_track_length = 3;                // points seen by fewer cameras are dropped

  // Neighbourhood tests (after the tests above), over the k nearest other points. 0 = skip both.
  int neighbours = 16;
  // Isolated: the point's spacing (mean distance to its 6 nearest points) exceeds isolation_factor ×
  // the median spacing of its k neighbours (a local test: a sparse area stays, a lone point goes).
  double isolation_factor = 3.0;
  // Off the local surface: a plane is fitted to the k neighbours by PCA, refitted twice on the
  // plane_inlier_fraction of them nearest to it (a trimmed, robust fit: a second surface or another
  // outlier among the neighbours does not tilt it); sigma = 1.4826 × the median distance of those
  // inliers to the plane. The point is dropped when its distance to the plane exceeds
  // max(plane_sigma_factor × sigma, plane_spacing_factor × the neighbours' median spacing).
  double plane_inlier_fraction = 0.75;
  double plane_sigma_factor = 6.0;
  double plane_spacing_factor = 1.5;
};

struct PointFilterReport {
  int64_t points_in = 0, points_out = 0;
  int64_t removed_non_finite = 0, removed_reprojection = 0, removed_short_track = 0;
  int64_t removed_isolated = 0, removed_off_plane = 0;
  // The criteria, as run (copied from the options), and what they found.
  double max_reprojection_error_px = 0;
  int min_track_length = 0, neighbours = 0;
  double isolation_factor = 0, plane_sigma_factor = 0, plane_spacing_factor = 0;
  double median_spacing_m = 0;  // median over the points of the mean distance to 6 neighbours
  double max_off_plane_m = 0;   // largest distance to its neighbours' plane among removed points
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
