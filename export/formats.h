// Every format `cinepath export` writes, declared once (as PDAL registers each stage with its name and
// description): its name, its file, its one-line description and its writer. Two kinds: missions (the
// flight model of the aircraft that flies it, which decides how waypoints are chosen, and the limits
// the format itself sets) and camera tracks (the planned camera for 3D packages and compositors, every
// sample, camera_track.h). Adding a format is one row in formats.cc plus its writer.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/drone_profile.h"
#include "export/camera_track.h"
#include "export/mission.h"
#include "export/platform.h"
#include "export/waypoint_selection.h"

namespace cinepath::exporter {

// How the target flies between waypoints and who aims the camera: formats with equal models share
// one Mission (one waypoint selection).
struct FlightModel {
  RoiTracking roi_tracking = RoiTracking::kNone;
  TurnModel turn_model = TurnModel::kStraight;
  bool operator==(const FlightModel&) const = default;
};

struct FormatWriterInput {
  const Mission& mission;
  Firmware firmware;
  AltitudeRef altitude_ref;
  const DroneProfile& drone;
  bool other_formats_use_rois;  // some other format of this run tracks points of interest
};

struct FormatOutput {
  std::string contents;
  std::vector<std::string> notes;
  int mission_items = 0;                   // MAVLink items (0 for the others)
  std::optional<Mission> checked_mission;  // when the writer changed the waypoints (MSDK merges close ones)
};

// A camera-track format's input: one track per drone (in the scene's frame), and the scene's GLB when
// the run has one (`--scene` with a mesh).
struct CameraWriterInput {
  const std::vector<CameraTrack>& tracks;
  std::string_view scene_glb;  // empty: none
  const std::string& scene_source;
};

struct CameraFile {
  std::string file_name;
  std::string contents;
};

enum class FormatKind { kMission, kCameraTrack };

struct FormatInfo {
  Format format;
  const char* name;                            // "qgc-plan"
  const char* file_name;                       // "mission.plan" ("<drone>.chan": one per drone)
  const char* description;                     // one line, for --help and docs/export.md
  bool mavlink;                                // MAVLink mission items (firmware-specific)
  FlightModel (*flight_model)(bool roi_auto);  // missions only
  FormatLimits limits;
  FormatOutput (*write)(const FormatWriterInput& input);  // missions only
  FormatKind kind = FormatKind::kMission;
  std::vector<CameraFile> (*write_cameras)(const CameraWriterInput& input) = nullptr;  // camera tracks only
};

const std::vector<FormatInfo>& Formats();  // in the order --help and docs/export.md list them
const FormatInfo& InfoOf(Format format);

const char* FormatName(Format format);
const char* FormatFileName(Format format);
Format ParseFormat(const std::string& name);  // InputError ("formats: ...") listing the known names
bool IsMavlinkFormat(Format format);
bool IsCameraTrackFormat(Format format);
FormatLimits LimitsOf(Format format);

}  // namespace cinepath::exporter
