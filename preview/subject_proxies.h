// The plan's subjects as render draws them: an upright cylinder per subject, standing on its base
// position, as tall as its height_m and 0.28 of that wide (a standing person: 1.8 m x 0.5 m), each in
// its own colour. Positions follow the plan's per-sample track, interpolated linearly in time.
// Intersected analytically in double, so a proxy moves without rebuilding the mesh's BVH.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/trajectory.h"
#include "preview/thin_lens_camera.h"

namespace cinepath::preview {

struct ProxyHit {
  double distance_m = 0;
  int subject = 0;  // index into Trajectory::subjects
  Eigen::Vector3d normal_enu = Eigen::Vector3d::Zero();
};

inline constexpr double kProxyRadiusPerHeight = 0.14;

// Where in one pinhole image the subjects can be seen: a rectangle of pixel coordinates per subject around
// its proxy's bounding box's eight corners as the camera projects them, wider by a margin that covers the
// rounding of the ray's direction; none for a box wholly behind the camera or outside the image; the whole
// image when a box stands across the camera's plane (and not outside the image). A pinhole ray
// through a pixel point outside every rectangle misses every proxy, so it need not be intersected with
// them (in a draft frame the subjects' tests were 7 % of the instructions).
class SubjectsInImage {
 public:
  static SubjectsInImage Everywhere() { return SubjectsInImage(); }
  // May a pinhole ray through the image point (x_px, y_px) hit a proxy?
  bool MaySee(double x_px, double y_px) const {
    if (everywhere_) return true;
    for (const Eigen::AlignedBox2d& box : boxes_) {
      if (box.contains(Eigen::Vector2d(x_px, y_px))) return true;
    }
    return false;
  }

 private:
  friend class SubjectProxies;
  SubjectsInImage() = default;
  bool everywhere_ = true;
  std::vector<Eigen::AlignedBox2d> boxes_;
};

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
  // Where the proxies standing on `bases` can be seen in the pinhole image of `camera` at `frame`.
  SubjectsInImage InImage(const std::vector<Eigen::Vector3d>& bases, const ThinLensCamera& camera,
                          const CameraFrame& frame) const;

 private:
  const Trajectory* plan_;
};

// Distinct colours (linear RGB) for subject i, cycling through a palette that stands out from
// terrain: orange, magenta, cyan, yellow, violet, lime.
Eigen::Vector3f SubjectColor(size_t subject);

}  // namespace cinepath::preview
