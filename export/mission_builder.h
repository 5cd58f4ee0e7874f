// From a plan's per-frame trajectory to a georeferenced Mission: resolves the WGS84 origin and the
// home point, checks the samples are finite, selects the waypoints and fills every altitude reference
// through core geodesy (EnuFrame) and the EGM96 geoid.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "core/geodesy.h"
#include "core/trajectory.h"
#include "export/mission.h"
#include "export/waypoint_selection.h"

namespace cinepath::exporter {

struct HomeSpec {  // --home LAT,LON,ALT (ALT metres AMSL, as QGC's plannedHomePosition)
  double lat_deg = 0;
  double lon_deg = 0;
  double amsl_m = 0;
};
// scene.json's WGS84 origin: {"origin": {"lat_deg", "lon_deg", "height_m"}} (ellipsoidal height;

// Parses "LAT,LON,ALT"; InputError naming `option` on a malformed value.
HomeSpec ParseHomeSpec(const std::string& text, const std::string& option);

struct MissionBuildOptions {
  std::string plan_name = "plan.json";   // for messages
  std::optional<Geodetic> scene_origin;  // from --scene, used when the plan has none
  std::optional<HomeSpec> home;          // default: the origin
  std::optional<DroneProfile> drone;     // the aircraft checked against; default: the plan's drone block
  bool absolute_altitudes = false;       // some requested output needs AMSL/ellipsoidal heights
  SelectionOptions selection;            // tolerances and roi_tracking (its `rois` are filled here)
  double transit_speed_mps = 5;          // legs across a "cut" between shots (recording off)
  // Detect point-of-interest stretches (roi.h) when selection.roi_tracking != kNone.
  double roi_min_duration_s = 2.0;
  TurnModel turn_model = TurnModel::kStraight;
  // kDjiCoordinatedTurn: the aircraft stops at a waypoint whose incoming leg is slower than this
  // (WPML's speed minimum: the slow leg is flown fast, then hovers; dji_wpml.h).
  double min_turn_speed_mps = 1.0;
};

// Points of interest (selection.roi_tracking != kNone) are detected per run (roi.h); with kHeading
// only stretches whose plan heading points at the point within max_angle_deg are kept. kDjiCoordinatedTurn
// then fits each waypoint's damping distance (dji_turns.h); max_deviation_reached_m is that of the
// modelled path, straight_deviation_reached_m that of straight legs.
// Waypoints are selected per continuous run of samples: a shot whose transition is "cut" starts a
// new run (its first sample and the previous shot's last sample both become waypoints, joined by a
// transit leg at `transit_speed_mps` with recording off).
// InputError for a plan with fewer than 1 sample, non-finite values (except focus at infinity),
// non-increasing times, or no origin where one is needed. Without any origin, --home places the ENU
// origin at home (only for relative altitudes).
Mission BuildMission(const Trajectory& trajectory, const MissionBuildOptions& options);

}  // namespace cinepath::exporter
