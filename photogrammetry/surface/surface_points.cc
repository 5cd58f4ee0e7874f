#include "photogrammetry/surface/surface_points.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <Eigen/Eigenvalues>

#include "core/error.h"
#include "photogrammetry/surface/cgal_point_search_internal.h"

namespace cinepath::photogrammetry {
namespace {

double MedianOf(std::vector<double> values) {
  if (values.empty()) return 0;
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[mid];
}

// The least-squares plane (centroid, unit normal) of `points` (PCA: the smallest eigenvector).
std::pair<Eigen::Vector3d, Eigen::Vector3d> FitPlane(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  return {centroid, solver.eigenvectors().col(0)};
}

// The local spacing: mean distance to this many nearest other points (as the trim step measures it).
constexpr int kSpacingNeighbours = 6;

struct NeighbourhoodTest {
  double spacing_m = 0;         // mean distance to the 6 nearest other points
  double plane_distance_m = 0;  // distance to the robust plane of those points
  double plane_sigma_m = 0;     // 1.4826 × median distance of the plane's inliers to it
  std::vector<uint32_t> neighbours;
};

// For every point of `positions`: its k nearest other points, its spacing and its distance to their
// robust plane (PointFilterOptions). Each point is independent: the result is the same at any thread
// count.
std::vector<NeighbourhoodTest> TestNeighbourhoods(const std::vector<Eigen::Vector3d>& positions,
                                                  const PointFilterOptions& options) {
  const internal::PointSearch search(positions);
  const int k = options.neighbours;
  const size_t inliers =
      std::clamp<size_t>(static_cast<size_t>(std::ceil(options.plane_inlier_fraction * k)), 3, static_cast<size_t>(k));
  std::vector<NeighbourhoodTest> out(positions.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, positions.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<Eigen::Vector3d> local;
    std::vector<std::pair<double, size_t>> residual;
    for (size_t i = r.begin(); i != r.end(); ++i) {
      NeighbourhoodTest& t = out[i];
      double sum = 0;
      int summed = 0;
      for (const auto& [d2, j] : search.Nearest(positions[i], k + 1)) {
        if (j == i || static_cast<int>(t.neighbours.size()) == k) continue;
        t.neighbours.push_back(j);
        if (summed < kSpacingNeighbours) {
          sum += std::sqrt(d2);
          ++summed;
        }
      }
      if (t.neighbours.size() < 3) continue;
      t.spacing_m = sum / summed;
      local.clear();
      for (uint32_t j : t.neighbours) local.push_back(positions[j]);
      auto plane = FitPlane(local);
      const size_t keep = std::min(inliers, local.size());
      for (int pass = 0; pass < 2; ++pass) {  // refit on the points nearest the plane
        residual.clear();
        for (size_t m = 0; m < local.size(); ++m) {
          residual.emplace_back(std::abs((local[m] - plane.first).dot(plane.second)), m);
        }
        std::sort(residual.begin(), residual.end());
        std::vector<Eigen::Vector3d> near;
        for (size_t m = 0; m < keep; ++m) near.push_back(local[residual[m].second]);
        plane = FitPlane(near);
      }
      std::vector<double> d;
      for (const auto& q : local) d.push_back(std::abs((q - plane.first).dot(plane.second)));
      std::sort(d.begin(), d.end());
      d.resize(keep);
      t.plane_sigma_m = 1.4826 * d[keep / 2];
      t.plane_distance_m = std::abs((positions[i] - plane.first).dot(plane.second));
    }
  });
  return out;
}

}  // namespace

Json PointFilterReport::ToJson() const {
  Json j;
  j["points_in"] = points_in;
  j["points_out"] = points_out;
  j["removed_non_finite"] = removed_non_finite;
  j["removed_reprojection"] = removed_reprojection;
  j["removed_short_track"] = removed_short_track;
  j["removed_isolated"] = removed_isolated;
  j["removed_off_plane"] = removed_off_plane;
  Json criteria;
  criteria["max_reprojection_error_px"] = max_reprojection_error_px;
  criteria["min_track_length"] = min_track_length;
  criteria["neighbours"] = neighbours;
  criteria["isolation_factor"] = isolation_factor;
  criteria["plane_sigma_factor"] = plane_sigma_factor;
  criteria["plane_spacing_factor"] = plane_spacing_factor;
  j["criteria"] = std::move(criteria);
  j["median_spacing_m"] = RoundToDecimals(median_spacing_m, 4);
  j["max_off_plane_removed_m"] = RoundToDecimals(max_off_plane_m, 4);
  return j;
}

PointCloud FilterPoints(const PointCloud& cloud, const PointFilterOptions& options, PointFilterReport* report_out) {
  const size_t n = cloud.size();
  auto check_size = [&](size_t size, const char* what) {
    if (size != 0 && size != n) {
      throw InputError(std::string("points: ") + what + ": one per point expected");
    }
  };
  check_size(cloud.colors_rgb.size(), "colors_rgb");
  check_size(cloud.normals.size(), "normals");
  check_size(cloud.reprojection_error_px.size(), "reprojection_error_px");
  check_size(cloud.observers.size(), "observers");

  PointFilterReport report;
  report.points_in = static_cast<int64_t>(n);
  report.max_reprojection_error_px = options.max_reprojection_error_px;
  report.min_track_length = options.min_track_length;
  report.neighbours = options.neighbours;
  report.isolation_factor = options.isolation_factor;
  report.plane_sigma_factor = options.plane_sigma_factor;
  report.plane_spacing_factor = options.plane_spacing_factor;
  std::vector<uint32_t> kept;
  for (size_t i = 0; i < n; ++i) {
    if (!cloud.positions_m[i].allFinite()) {
      ++report.removed_non_finite;
      continue;
    }
    if (!cloud.reprojection_error_px.empty() &&
        !(cloud.reprojection_error_px[i] <= options.max_reprojection_error_px)) {
      ++report.removed_reprojection;
      continue;
    }
    if (!cloud.observers.empty() && static_cast<int>(cloud.observers[i].size()) < options.min_track_length) {
      ++report.removed_short_track;
      continue;
    }
    kept.push_back(static_cast<uint32_t>(i));
  }

  // Neighbourhood tests, all measured on the same set (the order of removal does not matter).
  if (options.neighbours >= 3 && kept.size() > static_cast<size_t>(options.neighbours) + 1) {
    std::vector<Eigen::Vector3d> positions;
    positions.reserve(kept.size());
    for (uint32_t i : kept) positions.push_back(cloud.positions_m[i]);
    const std::vector<NeighbourhoodTest> tests = TestNeighbourhoods(positions, options);
    std::vector<double> spacings;
    for (const auto& t : tests) spacings.push_back(t.spacing_m);
    report.median_spacing_m = MedianOf(spacings);
    std::vector<uint32_t> survivors;
    std::vector<double> around;
    for (size_t m = 0; m < kept.size(); ++m) {
      const NeighbourhoodTest& t = tests[m];
      around.clear();
      for (uint32_t j : t.neighbours) around.push_back(tests[j].spacing_m);
      const double local_spacing_m = MedianOf(around);
      if (options.isolation_factor > 0 && t.spacing_m > options.isolation_factor * local_spacing_m) {
        ++report.removed_isolated;
        continue;
      }
      const double limit_m =
          std::max(options.plane_sigma_factor * t.plane_sigma_m, options.plane_spacing_factor * local_spacing_m);
      if (options.plane_sigma_factor > 0 && t.plane_distance_m > limit_m) {
        ++report.removed_off_plane;
        report.max_off_plane_m = std::max(report.max_off_plane_m, t.plane_distance_m);
        continue;
      }
      survivors.push_back(kept[m]);
    }
    kept.swap(survivors);
  }

  PointCloud out;
  out.camera_centers_m = cloud.camera_centers_m;
  for (uint32_t i : kept) {
    out.positions_m.push_back(cloud.positions_m[i]);
    if (cloud.has_colors()) out.colors_rgb.push_back(cloud.colors_rgb[i]);
    if (cloud.has_normals()) out.normals.push_back(cloud.normals[i]);
    if (!cloud.reprojection_error_px.empty()) {
      out.reprojection_error_px.push_back(cloud.reprojection_error_px[i]);
    }
    if (!cloud.observers.empty()) out.observers.push_back(cloud.observers[i]);
  }
  report.points_out = static_cast<int64_t>(out.size());
  if (report_out) *report_out = report;
  return out;
}

// Nadir test: for every observation, the direction from the point to the camera; the capture is
// nadir-like when the median of those directions' up component is above sin(45°). Without
// observations: the cloud's vertical extent (10–90 % percentiles) is under a quarter of its
// horizontal extent.
bool LooksLikeNadirCapture(const PointCloud& cloud) {
  std::vector<double> up;
  if (!cloud.observers.empty() && !cloud.camera_centers_m.empty()) {
    for (size_t i = 0; i < cloud.size() && i < cloud.observers.size(); ++i) {
      for (uint32_t c : cloud.observers[i]) {
        if (c >= cloud.camera_centers_m.size()) continue;
        const Eigen::Vector3d d = cloud.camera_centers_m[c] - cloud.positions_m[i];
        const double norm = d.norm();
        if (norm > 0 && std::isfinite(norm)) up.push_back(d.z() / norm);
      }
    }
  }
  if (!up.empty()) {
    std::nth_element(up.begin(), up.begin() + up.size() / 2, up.end());
    return up[up.size() / 2] > std::sqrt(0.5);
  }
  if (cloud.size() < 3) return true;
  std::vector<double> xs, ys, zs;
  for (const auto& p : cloud.positions_m) {
    if (!p.allFinite()) continue;
    xs.push_back(p.x());
    ys.push_back(p.y());
    zs.push_back(p.z());
  }
  auto spread = [](std::vector<double>& v) {
    if (v.empty()) return 0.0;
    const size_t lo = v.size() / 10, hi = v.size() - 1 - v.size() / 10;
    std::nth_element(v.begin(), v.begin() + lo, v.end());
    const double a = v[lo];
    std::nth_element(v.begin(), v.begin() + hi, v.end());
    return v[hi] - a;
  };
  const double horizontal = std::max(spread(xs), spread(ys));
  return spread(zs) < 0.25 * horizontal;
}

}  // namespace cinepath::photogrammetry
