#include "preview/subject_proxies.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "preview/thin_lens_camera.h"

namespace cinepath::preview {

Eigen::Vector3d SubjectProxies::BaseAt(size_t subject, double time_s, size_t hint) const {
  const auto& samples = plan_->samples;
  const auto& positions = plan_->subjects[subject].positions_enu_m;
  const size_t n = std::min(samples.size(), positions.size());
  if (n == 0) return Eigen::Vector3d::Zero();
  if (time_s <= samples[0].time_s || n == 1) return positions[0];
  if (time_s >= samples[n - 1].time_s) return positions[n - 1];
  const size_t b = SampleAfter(samples, n, time_s, hint);
  const size_t a = b - 1;
  const double span = samples[b].time_s - samples[a].time_s;
  const double w = span > 0 ? (time_s - samples[a].time_s) / span : 0;
  return positions[a] + w * (positions[b] - positions[a]);
}

void SubjectProxies::BasesAt(double time_s, std::vector<Eigen::Vector3d>* bases, size_t hint) const {
  bases->resize(plan_->subjects.size());
  for (size_t i = 0; i < bases->size(); ++i) (*bases)[i] = BaseAt(i, time_s, hint);
}

std::optional<ProxyHit> SubjectProxies::Intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                                  double time_s, double max_distance_m) const {
  std::vector<Eigen::Vector3d> bases;
  BasesAt(time_s, &bases);
  return Intersect(origin, direction, bases, max_distance_m);
}

std::optional<ProxyHit> SubjectProxies::Intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                                  const std::vector<Eigen::Vector3d>& bases,
                                                  double max_distance_m) const {
  std::optional<ProxyHit> best;
  for (size_t i = 0; i < plan_->subjects.size(); ++i) {
    const double height = plan_->subjects[i].height_m;
    const double radius = std::max(0.05, kProxyRadiusPerHeight * height);
    const Eigen::Vector3d o = origin - bases[i];
    auto consider = [&](double t, const Eigen::Vector3d& normal) {
      if (t > 1e-6 && t < max_distance_m && (!best || t < best->distance_m)) best = ProxyHit{t, int(i), normal};
    };
    // The side: |(o + t d)_xy| = r, 0 <= z <= height.
    const double a = direction.x() * direction.x() + direction.y() * direction.y();
    const double b = o.x() * direction.x() + o.y() * direction.y();
    const double c = o.x() * o.x() + o.y() * o.y() - radius * radius;
    if (a > 0) {
      const double disc = b * b - a * c;
      // The ray's line passes outside the circle seen from above: neither the side nor the top cap (a
      // disk of the same circle) can be hit. Most rays of a frame end here.
      if (disc < 0) continue;
      const double root = std::sqrt(disc);
      for (double t : {(-b - root) / a, (-b + root) / a}) {
        const Eigen::Vector3d p = o + t * direction;
        if (p.z() >= 0 && p.z() <= height) {
          consider(t, Eigen::Vector3d(p.x(), p.y(), 0).normalized());
          break;
        }
      }
    }
    // The top cap (seen from above: drone shots look down on their subjects).
    if (direction.z() != 0) {
      const double t = (height - o.z()) / direction.z();
      const Eigen::Vector3d p = o + t * direction;
      if (p.x() * p.x() + p.y() * p.y() <= radius * radius) consider(t, Eigen::Vector3d::UnitZ());
    }
  }
  return best;
}

SubjectsInImage SubjectProxies::InImage(const std::vector<Eigen::Vector3d>& bases, const ThinLensCamera& camera,
                                        const CameraFrame& frame) const {
  // Far more than the rounding of a ray's direction (~1e-16 of it) and of the projection.
  constexpr double kMarginPx = 2;
  SubjectsInImage seen;
  if (bases.size() != plan_->subjects.size()) return seen;
  for (size_t i = 0; i < bases.size(); ++i) {
    const double height = plan_->subjects[i].height_m;
    const double radius = std::max(0.05, kProxyRadiusPerHeight * height);
    // Each corner's image point and depth, and the four sides of the image (a margin wider) as planes
    // through the camera's centre: x_px z / W >= -m z / W is the left one, and so on. A box wholly behind
    // the camera or wholly outside one side (the box is convex) is not seen by any ray of the image.
    const double w = camera.width_px(), h = camera.height_px();
    Eigen::AlignedBox2d box;
    int behind = 0, left = 0, right = 0, above = 0, below = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d p = bases[i] + Eigen::Vector3d(corner & 1 ? radius : -radius, corner & 2 ? radius : -radius,
                                                           corner & 4 ? std::max(0.0, height) : std::min(0.0, height));
      double z = 0;
      const Eigen::Vector2d xy = camera.Project(frame, p, &z);
      if (z == 0 || !std::isfinite(z) || !xy.allFinite()) return seen;  // on the camera's plane, or not a number
      const double hx = xy.x() * z / w, hy = xy.y() * z / h;
      behind += z <= 0;
      left += hx < -kMarginPx * z / w;
      right += hx > (w + kMarginPx) * z / w;
      above += hy < -kMarginPx * z / h;
      below += hy > (h + kMarginPx) * z / h;
      box.extend(xy);
    }
    if (behind == 8 || left == 8 || right == 8 || above == 8 || below == 8) continue;
    if (behind > 0) return seen;  // across the camera's plane and not outside a side: no bound
    box.min().array() -= kMarginPx;
    box.max().array() += kMarginPx;
    seen.boxes_.push_back(box);
  }
  seen.everywhere_ = false;
  return seen;
}

Eigen::Vector3f SubjectColor(size_t subject) {
  static const std::array<Eigen::Vector3f, 6> palette = {
      Eigen::Vector3f(0.90f, 0.30f, 0.02f), Eigen::Vector3f(0.80f, 0.05f, 0.60f), Eigen::Vector3f(0.02f, 0.65f, 0.80f),
      Eigen::Vector3f(0.90f, 0.80f, 0.02f), Eigen::Vector3f(0.40f, 0.15f, 0.90f), Eigen::Vector3f(0.30f, 0.85f, 0.05f)};
  return palette[subject % palette.size()];
}

}  // namespace cinepath::preview
