#include "export/flight_export.h"

#include <cmath>
#include <utility>

#include "core/error.h"
#include "core/geoid.h"
#include "core/number_format.h"
#include "export/takeoff.h"

namespace cinepath::exporter {
namespace {

// The home of one flight: its `home_enu_m`; else --home, checked against the mesh's ground; else the
// ground under its first sample; else none (the mission builder takes the origin).
void PlaceHome(const DroneFlight& flight, const FlightExportOptions& options, ExportOptions& out) {
  const std::optional<Geodetic> origin = flight.plan.origin ? flight.plan.origin : out.build.scene_origin;
  if (flight.home_enu_m) {
    if (!origin) {
      throw InputError(options.plan_name + ": flights[" + flight.name +
                       "].home_enu_m: the plan has no WGS84 origin to place it; pass --scene");
    }
    const Geodetic home = EnuFrame(*origin).GeodeticFromEnu(*flight.home_enu_m);
    out.build.home = HomeSpec{home.lat_deg, home.lon_deg,
                              Egm96Geoid::Default().AmslFromEllipsoidalM(home.lat_deg, home.lon_deg, home.height_m)};
    return;
  }
  if (!options.ground) return;
  if (!out.build.home) {
    out.build.home = TakeoffOnGround(flight.plan, *options.scene_origin, *options.ground);
    return;
  }
  const auto check = CheckHomeAgainstGround(*out.build.home, *options.scene_origin, *options.ground);
  if (!check || std::abs(check->difference_m) <= options.takeoff_tolerance_m) return;
  const std::string message = "--home: altitude " + FormatFixed(out.build.home->amsl_m, 2) + " m AMSL lies " +
                              FormatFixed(check->difference_m, 2) + " m from the mesh's ground (" +
                              FormatFixed(check->ground_amsl_m, 2) + " m AMSL) there, beyond --takeoff-tolerance-m " +
                              FormatSignificant(options.takeoff_tolerance_m, 3) +
                              " m: every relative altitude shifts by it";
  if (options.strict) throw InfeasibleError(message + " (--strict; nothing written)");
  if (options.warn) options.warn(message);
}

}  // namespace

std::vector<FlightExport> ExportFlights(const TeamPlan& plan, const FlightExportOptions& options) {
  const bool named = !plan.single;  // a plan of several drones: messages name the drone
  if (named && options.shared.build.home) {
    throw InputError("--home: " + options.plan_name + " holds " + std::to_string(plan.flights.size()) +
                     " drones, and one --home cannot be every drone's take-off point; give each drone its "
                     "`home_enu_m` or `home` in shots.json (docs/export.md, \"Several drones\")");
  }
  if (named) {
    for (const auto& flight : plan.flights) CheckDroneFolderName(flight.name, options.plan_name);
  }
  std::vector<FlightExport> exports;
  for (const auto& flight : plan.flights) {
    ExportOptions flight_options = options.shared;
    flight_options.build.plan_name = named ? options.plan_name + " (drone " + flight.name + ")" : options.plan_name;
    if (options.scene_origin) flight_options.build.scene_origin = options.scene_origin;
    PlaceHome(flight, options, flight_options);
    try {
      ExportResult result = ExportMission(flight.plan, flight_options);
      exports.push_back({flight.name, std::move(flight_options), std::move(result)});
    } catch (const InfeasibleError& e) {
      if (!named) throw;
      throw InfeasibleError("drone " + flight.name + ": " + e.what());
    } catch (const InputError& e) {
      if (!named) throw;
      throw InputError("drone " + flight.name + ": " + e.what());
    }
  }
  return exports;
}

}  // namespace cinepath::exporter
