// The plan's subjects as render draws them: an upright cylinder per subject, standing on its base
// position, as tall as its height_m and 0.28 of that wide (a standing person: 1.8 m x 0.5 m), each in
// its own colour. Positions follow the plan's per-sample track, interpolated linearly in time.
// Intersected analytically in double, so a proxy moves without rebuilding the mesh's BVH.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "core/trajectory.h"

namespace cinepath::preview {

struct ProxyHit {
  double distance_m = 0;
  int subject = 0;  // index into Trajectory::subjects
  Eigen::Vector3d normal_enu = Eigen::Vector3d::Zero();
};

inline constexpr double kProxyRadiusPerHeight = 0.14;

class SubjectProxies {
 public:
  explicit SubjectProxies(const Trajectory& plan) : plan_(&plan) {}

  bool empty() const { return plan_->subjects.empty(); }
  // The base of subject i at time t (linear between samples, clamped at the ends).
  // `hint`: a sample index near t (thin_lens_camera.h SampleAfter), or none.
  Eigen::Vector3d BaseAt(size_t subject, double time_s, size_t hint = 0) const;
  // Every subject's base at time t (BaseAt of each): computed once for the many rays of one instant.
  void BasesAt(double time_s, std::vector<Eigen::Vector3d>* bases, size_t hint = 0) const;
  // The closest proxy hit along the ray within (0, max_distance_m), at time t.
  std::optional<ProxyHit> Intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double time_s,
                                    double max_distance_m) const;
  // The same, with the subjects standing on `bases` (from BasesAt).
  std::optional<ProxyHit> Intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                    const std::vector<Eigen::Vector3d>& bases, double max_distance_m) const;

 private:
  const Trajectory* plan_;
};

// Distinct colours (linear RGB) for subject i, cycling through a palette that stands out from
// terrain: orange, magenta, cyan, yellow, violet, lime.
Eigen::Vector3f SubjectColor(size_t subject);

}  // namespace cinepath::preview
