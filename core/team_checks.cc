#include "core/team_checks.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/optics.h"

namespace cinepath {
namespace {

// Merges broken samples of one (limit, drone, other) into ranges.
class ConflictTrack {
 public:
  ConflictTrack(TeamConflict prototype, bool is_minimum, std::vector<TeamConflict>* out)
      : prototype_(std::move(prototype)), is_minimum_(is_minimum), out_(out) {}

  void Add(size_t k, double t, bool broken, double value) {
    if (!broken) return;
    if (open_ && last_ + 1 == k) {
      TeamConflict& c = out_->back();
      c.end_time_s = t;
      c.worst_value = is_minimum_ ? std::min(c.worst_value, value) : std::max(c.worst_value, value);
    } else {
      TeamConflict c = prototype_;
      c.start_time_s = c.end_time_s = t;
      c.worst_value = value;
      out_->push_back(std::move(c));
    }
    open_ = true;
    last_ = k;
  }

 private:
  TeamConflict prototype_;
  bool is_minimum_;
  std::vector<TeamConflict>* out_;
  bool open_ = false;
  size_t last_ = 0;
};

const TrajectorySample& SampleAt(const DroneFlight& flight, size_t k) {
  return flight.plan.samples[std::min(k, flight.plan.samples.size() - 1)];
}

}  // namespace

double TeamMinSeparationM(const TeamPlan& plan) {
  double m = 0;
  for (const auto& f : plan.flights) m = std::max(m, f.plan.drone.min_separation_m);
  return m;
}

double ProjectedBodyDiameterPx(const CameraSpec& camera, const Eigen::Vector3d& camera_position_enu_m,
                               const Eigen::Quaterniond& world_from_camera, double focal_length_mm,
                               const Eigen::Vector3d& body_position_enu_m, double body_radius_m) {
  const Eigen::Vector3d c = world_from_camera.conjugate() * (body_position_enu_m - camera_position_enu_m);
  if (c.z() <= body_radius_m) return 0;  // behind, or the camera inside the body (separation reports it)
  const ImageExtentMm image = camera.image_extent_mm();
  const double focal_px = focal_length_mm / image.width_mm * camera.width_px;
  // The sphere's silhouette from its centre's depth: angular radius asin(r / |c|), projected at the
  // centre's depth (exact on the axis, a few per cent small at the frame's corners).
  const double radius_px = focal_px * std::tan(std::asin(std::min(1.0, body_radius_m / c.norm())));
  const double u = focal_px * c.x() / c.z();  // from the image centre, x right
  const double v = focal_px * c.y() / c.z();  // y down
  const double half_w = 0.5 * camera.width_px, half_h = 0.5 * camera.height_px;
  if (std::fabs(u) > half_w + radius_px || std::fabs(v) > half_h + radius_px) return 0;
  return 2 * radius_px;
}

void CheckTeam(TeamPlan& plan) {
  plan.team.min_separation_m = TeamMinSeparationM(plan);
  plan.team.conflicts.clear();
  const size_t n = plan.SampleCount();
  const size_t drones = plan.flights.size();
  for (const auto& f : plan.flights) CINEPATH_CHECK(!f.plan.samples.empty());
  auto time_at = [&](size_t k) { return static_cast<double>(k) / plan.frame_rate_hz; };

  for (size_t a = 0; a < drones; ++a) {
    for (size_t b = a + 1; b < drones; ++b) {
      const double limit =
          std::max(plan.flights[a].plan.drone.min_separation_m, plan.flights[b].plan.drone.min_separation_m);
      ConflictTrack track({.limit = "separation",
                           .drone = plan.flights[a].name,
                           .other = plan.flights[b].name,
                           .limit_value = limit,
                           .unit = "m"},
                          true, &plan.team.conflicts);
      for (size_t k = 0; k < n; ++k) {
        const double d =
            (SampleAt(plan.flights[a], k).position_enu_m - SampleAt(plan.flights[b], k).position_enu_m).norm();
        track.Add(k, time_at(k), d < limit - 1e-9, d);
      }
    }
  }

  for (size_t viewer = 0; viewer < drones; ++viewer) {
    const DroneFlight& cam = plan.flights[viewer];
    for (size_t seen = 0; seen < drones; ++seen) {
      if (seen == viewer) continue;
      const DroneFlight& body = plan.flights[seen];
      ConflictTrack track({.limit = "in_shot",
                           .drone = cam.name,
                           .other = body.name,
                           .limit_value = kInShotMinDiameterPx,
                           .unit = "px"},
                          false, &plan.team.conflicts);
      for (size_t k = 0; k < n; ++k) {
        const double t = time_at(k);
        if (!plan.edit.empty() && LiveFlightAt(plan, t) != static_cast<int>(viewer)) continue;
        const TrajectorySample& s = SampleAt(cam, k);
        const double diameter =
            ProjectedBodyDiameterPx(cam.plan.camera, s.position_enu_m, s.world_from_camera, s.focal_length_mm,
                                    SampleAt(body, k).position_enu_m, body.plan.drone.body_radius_m);
        track.Add(k, t, diameter >= kInShotMinDiameterPx, diameter);
      }
    }
  }
}

}  // namespace cinepath
