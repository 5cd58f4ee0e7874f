#include "shots/plan_warnings.h"

#include <algorithm>
#include <cmath>

#include "core/number_format.h"

namespace cinepath::shots {

std::vector<std::string> StopsDeadWarnings(const ShotList& list, const TeamPlan& plan) {
  std::vector<std::string> warnings;
  const double frame_s = 1.0 / plan.frame_rate_hz;
  for (const DroneFlight& flight : plan.flights) {
    for (const ShotSpan& shot : flight.plan.shots) {
      const int index = list.FindActor(shot.subject);
      if (index < 0) continue;
      const Actor& actor = list.actors[index];
      const double last_s = actor.path().times().back();
      if (last_s < shot.start_time_s || last_s > shot.end_time_s - frame_s) continue;
      const double speed = actor.SpeedAtLastKeyMS();
      if (speed <= kStopsDeadMS) continue;
      warnings.push_back(
          "actor \"" + actor.name() + "\" stops dead at its last key (" + FormatSignificant(last_s, 6) + " s, from " +
          FormatSignificant(speed, 3) + " m/s), and shot \"" + shot.name + "\"" +
          (plan.single || plan.flights.size() == 1 ? "" : " of drone \"" + flight.name + "\"") + " follows it to " +
          FormatSignificant(shot.end_time_s, 6) +
          " s: the camera eases into the stop, but its aim stops dead with the actor; add a key where the "
          "actor comes to rest, or end the shot there");
    }
  }
  return warnings;
}

std::vector<std::string> FloatingActorWarnings(const ShotList& list) {
  std::vector<std::string> warnings;
  if (!list.ground) return warnings;
  for (const Actor& actor : list.actors) {
    if (actor.kept_on_ground()) continue;
    // The key farthest off the ground: its field, the base's height over the ground (< 0: buried by that
    // much, head to surface), and where.
    const Actor::AbsoluteHeightKey* worst = nullptr;
    double worst_off_m = 0, worst_over_m = 0;
    Eigen::Vector3d worst_at = Eigen::Vector3d::Zero();
    for (const Actor::AbsoluteHeightKey& key : actor.absolute_height_keys()) {
      const Eigen::Vector3d p = actor.path().Position(actor.path().times()[key.key]);
      const double head_m = p.z() + actor.height_m();
      double over_m = 0;  // > 0: floating by this much; < 0: the surface this far above the head
      if (const auto below = list.ground->SurfaceUpM(p.x(), p.y(), p.z() + std::max(actor.height_m(), 2.0))) {
        over_m = p.z() - *below;
        if (over_m <= kFloatsAboveGroundM) continue;
      } else if (const auto top = list.ground->SurfaceUpM(p.x(), p.y()); top && *top > head_m) {
        over_m = head_m - *top;
      } else {
        continue;  // nothing of the mesh there
      }
      if (std::fabs(over_m) > worst_off_m) {
        worst = &key, worst_off_m = std::fabs(over_m), worst_over_m = over_m, worst_at = p;
      }
    }
    if (!worst) continue;
    const std::string where =
        "(" + FormatSignificant(worst_at.x(), 4) + ", " + FormatSignificant(worst_at.y(), 4) + ")";
    warnings.push_back(
        "actor \"" + actor.name() + "\" (" + worst->field + ") " +
        (worst_over_m > 0 ? "stands " + FormatSignificant(worst_over_m, 3) + " m above the scene's ground (" +
                                list.ground->source() + ") at " + where
                          : "has its head " + FormatSignificant(-worst_over_m, 3) + " m under the scene's surface (" +
                                list.ground->source() + ") at " + where) +
        ", at the absolute height given (up " + FormatSignificant(worst_at.z(), 4) +
        " m); give the position without its height ([east_m, north_m], or \"above_ground_m\" in place of a "
        "lat/lon height) to stand it on the ground");
  }
  return warnings;
}

}  // namespace cinepath::shots
