#include "photogrammetry/mesh/view_dependent_budget.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/optics.h"

namespace cinepath::photogrammetry {

std::vector<PlanCamera> CamerasFromPlan(const Trajectory& plan, const std::string& source) {
  if (plan.samples.empty()) throw InputError(Located(source + ": samples", "the plan has no sample (no camera)"));
  const ImageExtentMm extent = plan.camera.image_extent_mm();
  std::vector<PlanCamera> cameras;
  cameras.reserve(plan.samples.size());
  for (size_t i = 0; i < plan.samples.size(); ++i) {
    const TrajectorySample& s = plan.samples[i];
    PlanCamera c;
    c.sample_index = static_cast<int>(i);
    c.time_s = s.time_s;
    c.center_enu_m = s.position_enu_m;
    c.camera_from_world = s.world_from_camera.normalized().toRotationMatrix().transpose();
    // The image spans the sensor's full width (core/optics.h sensor fit), as render draws it.
    c.focal_px = s.focal_length_mm * plan.camera.width_px / extent.width_mm;
    c.width_px = plan.camera.width_px;
    c.height_px = plan.camera.height_px;
    cameras.push_back(c);
  }
  return cameras;
}

PointView FinestView(const Eigen::Vector3d& point_enu_m, const std::vector<PlanCamera>& cameras) {
  PointView best;
  for (size_t k = 0; k < cameras.size(); ++k) {
    const PlanCamera& c = cameras[k];
    const Eigen::Vector3d d = point_enu_m - c.center_enu_m;
    const Eigen::Vector3d p = c.camera_from_world * d;
    if (!(p.z() > 1e-3)) continue;  // behind (or at) the camera
    const double u = c.focal_px * p.x() / p.z() + 0.5 * c.width_px;
    const double v = c.focal_px * p.y() / p.z() + 0.5 * c.height_px;
    if (u < 0 || u > c.width_px || v < 0 || v > c.height_px) continue;
    const double metres_per_px = p.z() * p.z() / (c.focal_px * d.norm());
    if (metres_per_px < best.metres_per_px) {
      best.metres_per_px = metres_per_px;
      best.camera = static_cast<int>(k);
      best.depth_m = p.z();
    }
  }
  return best;
}

std::vector<PointView> FinestViews(const std::vector<Eigen::Vector3d>& points_enu_m,
                                   const std::vector<PlanCamera>& cameras) {
  std::vector<PointView> views(points_enu_m.size());
  tbb::parallel_for(size_t{0}, points_enu_m.size(), [&](size_t i) { views[i] = FinestView(points_enu_m[i], cameras); });
  return views;
}

}  // namespace cinepath::photogrammetry
