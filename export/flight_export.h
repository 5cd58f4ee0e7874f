// `cinepath export` for every flight of a plan: a one-drone plan is a team of one. Each flight's home is
// worked out (its `home_enu_m` through the origin and the EGM96 geoid, --home checked against the mesh's
// ground, or the ground under its first sample), then its missions are built and checked against its own
// profile (--drone overrides for all) by ExportMission. Nothing is written here; the CLI places the files
// (a "cinepath.plan/1" plan into OUTPUT, a plan of several drones into OUTPUT/<drone>/).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/geodesy.h"
#include "core/ground.h"
#include "core/team_plan.h"
#include "export/exporter.h"

namespace cinepath::exporter {

struct FlightExportOptions {
  ExportOptions shared;                          // every flight's; shared.build.home is --home (one drone only)
  std::string plan_name;                         // the plan file, for messages
  std::optional<Geodetic> scene_origin;          // --scene's origin (the plan's own origin wins where it has one)
  const Ground* ground = nullptr;                // --scene's mesh's ground, when it has a mesh
  double takeoff_tolerance_m = 3;                // --home against the ground: a larger difference is warned about
  bool strict = false;                           // ... or refused (InfeasibleError)
  std::function<void(const std::string&)> warn;  // receives the warnings (may be empty)
};

struct FlightExport {
  std::string name;       // the drone's name
  ExportOptions options;  // the options its missions were built with (its home, its plan name)
  ExportResult result;
};

// One FlightExport per flight, in the plan's order. Throws as ExportMission does (the message names the
// drone in a plan of several), and InputError for --home with several drones or a home_enu_m without an
// origin.
std::vector<FlightExport> ExportFlights(const TeamPlan& plan, const FlightExportOptions& options);

}  // namespace cinepath::exporter
