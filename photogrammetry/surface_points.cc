#include "photogrammetry/surface_points.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace cinepath::photogrammetry {

Json PointFilterReport::ToJson() const {
  Json j;
  j["points_in"] = points_in;
  j["points_out"] = points_out;
  j["removed_non_finite"] = removed_non_finite;
  j["removed_reprojection"] = removed_reprojection;
  j["removed_short_track"] = removed_short_track;
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
  PointCloud out;
  out.camera_centers_m = cloud.camera_centers_m;
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
