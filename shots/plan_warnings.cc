#include "shots/plan_warnings.h"

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

}  // namespace cinepath::shots
