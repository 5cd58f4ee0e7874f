// `cinepath export` as a library call: plan trajectory in, mission files (bytes) and a report out.
// Nothing is written here; the CLI stages the files with AtomicOutputs.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/json.h"
#include "core/trajectory.h"
#include "export/formats.h"
#include "export/mission.h"
#include "export/mission_builder.h"
#include "export/platform.h"
#include "export/validation.h"

namespace cinepath::exporter {

// Points of interest (roi.h): kAuto detects them and hands the pointing to the target where the
// format can (MAVLink ROI, DJI towardPOI, Litchi POI); kOff always lists headings and gimbal angles.
enum class RoiMode { kAuto, kOff };

struct ExportOptions {
  std::vector<Format> formats;
  // --firmware: the MAVLink dialect for every drone. Unset, each drone's profile says (FirmwareOf).
  std::optional<Firmware> firmware;
  AltitudeRef altitude_ref = AltitudeRef::kRelative;
  bool force = false;  // write even when a limit is broken (still reported)
  RoiMode roi = RoiMode::kAuto;
  MissionBuildOptions build;  // origin/home/drone/selection
  void Check() const;         // InputError: no format, duplicate format, a format that cannot hold altitude_ref
};

struct ExportFile {
  std::string file_name;  // relative to the output folder
  std::string contents;
};

struct FormatReport {
  Format format;
  std::string file_name;
  int mission_items = 0;  // MAVLink items (0 for DJI/Litchi)
  int mission = 0;        // index into ExportResult::missions (the waypoints this format carries)
  std::vector<std::string> notes;
  std::vector<Violation> violations;
};

// Waypoints are chosen per flight model: MAVLink and Litchi fly straight legs and track points of
// interest with the camera; DJI WPML flies coordinated turns and turns its nose to the point; MSDK v4
// flies straight legs with explicit headings. Formats with the same model share one Mission.
struct ExportResult {
  Mission mission;  // the first format's (= missions[reports[0].mission])
  std::vector<Mission> missions;
  std::vector<ExportFile> files;
  std::vector<FormatReport> reports;
  std::string drone_name;              // the drone profile the missions were checked against
  Firmware firmware = Firmware::kPx4;  // the MAVLink dialect the missions were written in
  bool has_violations() const;
};

// The MAVLink firmware of a drone profile: its own ("px4" or "ardupilot"); PX4's dialect, the generic
// MAVLink one, for a profile that flies neither (DJI, a custom profile).
Firmware FirmwareOf(const DroneProfile& profile);

// Throws InputError for bad input, InfeasibleError (naming the waypoint and limit of the first
// violations) when a limit is broken and !force.
ExportResult ExportMission(const Trajectory& trajectory, const ExportOptions& options);

// The report as JSON (report.json / --json) and as the human summary printed by the CLI.
Json ReportJson(const ExportResult& result, const ExportOptions& options);
std::string ReportText(const ExportResult& result, const ExportOptions& options);

}  // namespace cinepath::exporter
