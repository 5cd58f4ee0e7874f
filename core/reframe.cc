#include "core/reframe.h"

namespace cinepath {

Trajectory ReframeToOrigin(Trajectory plan, const Geodetic& origin) {
  if (!plan.origin) return plan;
  const Geodetic& from = *plan.origin;
  if (from.lat_deg == origin.lat_deg && from.lon_deg == origin.lon_deg && from.height_m == origin.height_m) {
    return plan;
  }
  const EnuFrame source(from), target(origin);
  const Eigen::Quaterniond turn(EnuFromEnu(origin, from).linear());
  auto point = [&](const Eigen::Vector3d& p) { return target.EnuFromEcef(source.EcefFromEnu(p)); };
  for (TrajectorySample& s : plan.samples) {
    s.position_enu_m = point(s.position_enu_m);
    s.world_from_camera = (turn * s.world_from_camera).normalized();
  }
  for (Keyframe& k : plan.keyframes) {
    k.position_enu_m = point(k.position_enu_m);
    k.world_from_camera = (turn * k.world_from_camera).normalized();
  }
  for (SubjectTrack& subject : plan.subjects) {
    for (Eigen::Vector3d& p : subject.positions_enu_m) p = point(p);
  }
  plan.origin = origin;
  return plan;
}

TeamPlan ReframeToOrigin(TeamPlan plan, const Geodetic& origin) {
  if (!plan.origin) return plan;
  const EnuFrame source(*plan.origin), target(origin);
  for (DroneFlight& f : plan.flights) {
    f.plan = ReframeToOrigin(std::move(f.plan), origin);
    if (f.home_enu_m) f.home_enu_m = target.EnuFromEcef(source.EcefFromEnu(*f.home_enu_m));
  }
  plan.origin = origin;
  return plan;
}

Eigen::Isometry3d EnuFromEnu(const Geodetic& to, const Geodetic& from) {
  const EnuFrame source(from), target(to);
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.linear() = target.enu_from_ecef_rotation() * source.enu_from_ecef_rotation().transpose();
  motion.translation() = target.EnuFromEcef(source.EcefFromEnu(Eigen::Vector3d::Zero()));
  return motion;
}

}  // namespace cinepath
