#include "export/formats.h"

#include "core/error.h"
#include "export/dji_msdk_json.h"
#include "export/dji_wpml.h"
#include "export/gltf_camera.h"
#include "export/litchi_csv.h"
#include "export/mavlink_bin.h"
#include "export/mavlink_mission.h"
#include "export/msdk_spacing.h"
#include "export/nuke_chan.h"
#include "export/qgc_plan.h"
#include "export/qgc_wpl.h"

namespace cinepath::exporter {
namespace {

// Flight models. MAVLink autopilots and Litchi fly straight legs and can aim the camera at a point
// of interest; DJI WPML flies coordinated turns and turns the nose to the point; MSDK v4 flies straight
// legs with explicit headings (its point-of-interest heading mode is mission-wide).
FlightModel StraightTrackingCamera(bool roi_auto) {
  return {roi_auto ? RoiTracking::kCamera : RoiTracking::kNone, TurnModel::kStraight};
}
FlightModel CoordinatedTurnsTrackingHeading(bool roi_auto) {
  return {roi_auto ? RoiTracking::kHeading : RoiTracking::kNone, TurnModel::kDjiCoordinatedTurn};
}
FlightModel StraightWithHeadings(bool) { return {RoiTracking::kNone, TurnModel::kStraight}; }

// The MAVLink writers share the mission items.
template <std::string (*kWrite)(const FormatWriterInput&, const MavMission&)>
FormatOutput WriteMavlink(const FormatWriterInput& in) {
  const MavMission items = BuildMavMission(in.mission, in.firmware, in.altitude_ref);
  FormatOutput out;
  out.notes = items.notes;
  out.mission_items = static_cast<int>(items.items.size());
  out.contents = kWrite(in, items);
  return out;
}
std::string QgcPlanText(const FormatWriterInput& in, const MavMission& items) {
  return WriteQgcPlan(in.mission, items, in.firmware, in.altitude_ref);
}
std::string QgcWplText(const FormatWriterInput& in, const MavMission& items) { return WriteQgcWpl(in.mission, items); }
std::string MavlinkBinBytes(const FormatWriterInput& in, const MavMission& items) {
  return WriteMavlinkBin(in.mission, items, in.firmware);
}

FormatOutput WriteWpml(const FormatWriterInput& in) {
  const WpmlDocuments docs = WriteWpmlDocuments(in.mission, in.drone, in.altitude_ref);
  return {WriteDjiKmz(docs), docs.notes, 0, std::nullopt};
}

FormatOutput WriteMsdk(const FormatWriterInput& in) {
  std::vector<std::string> merge_notes;
  Mission merged = MergeCloseWaypoints(in.mission, LimitsOf(Format::kDjiMsdkJson).min_spacing_m, merge_notes);
  MsdkJson json = WriteDjiMsdkJson(merged);
  FormatOutput out;
  out.notes = json.notes;
  out.notes.insert(out.notes.end(), merge_notes.begin(), merge_notes.end());
  if (in.other_formats_use_rois) {
    out.notes.push_back(
        "points of interest not used: MSDK v4's headingMode TOWARD_POINT_OF_INTEREST is mission-wide; headings and "
        "gimbal pitch are per waypoint");
  }
  out.contents = std::move(json.text);
  out.checked_mission = std::move(merged);
  return out;
}

FormatOutput WriteLitchi(const FormatWriterInput& in) {
  LitchiCsv csv = WriteLitchiCsv(in.mission);
  return {std::move(csv.text), std::move(csv.notes), 0, std::nullopt};
}

FormatLimits MavlinkLimits() {
  FormatLimits l;
  l.max_waypoints = 65535;  // seq is uint16
  return l;
}

// MSDK v5 refuses fewer than 2 or more than 65535 waypoints; speeds [1, 15] m/s. A slower leg is flown
// at 1 m/s followed by a hover that keeps the timing (dji_wpml.h), so no minimum here.
FormatLimits WpmlLimits() {
  FormatLimits l;
  l.min_waypoints = 2;
  l.max_waypoints = 65535;
  l.max_speed_mps = 15;
  return l;
}

// MSDK v4 WaypointMission: 2-99 waypoints, 0.5-2000 m apart, altitude -200..500 m relative, gimbal pitch
// -90..0, speed 0..15 m/s.
FormatLimits MsdkLimits() {
  FormatLimits l;
  l.min_waypoints = 2;
  l.max_waypoints = 99;
  l.max_speed_mps = 15;
  l.min_spacing_m = 0.5;
  l.max_spacing_m = 2000;
  l.min_relative_alt_m = -200;
  l.max_relative_alt_m = 500;
  l.min_gimbal_pitch_deg = -90;
  l.max_gimbal_pitch_deg = 0;
  return l;
}

// Litchi: up to 10 000 waypoints (since 2022); DJI speeds up to 15 m/s; gimbal -90..30.
FormatLimits LitchiLimits() {
  FormatLimits l;
  l.min_waypoints = 2;
  l.max_waypoints = 10000;
  l.max_speed_mps = 15;
  l.min_gimbal_pitch_deg = -90;
  l.max_gimbal_pitch_deg = 30;
  return l;
}

// Camera tracks: one GLB with every drone's camera (and the scene), or one .chan per drone.
std::vector<CameraFile> WriteGltfCameraFile(const CameraWriterInput& in) {
  return {{"previs.glb", WriteGltfCamera(in.tracks, in.scene_glb, in.scene_source)}};
}
std::vector<CameraFile> WriteNukeChanFiles(const CameraWriterInput& in) {
  std::vector<CameraFile> files;
  for (const CameraTrack& track : in.tracks) files.push_back({track.name + ".chan", WriteNukeChan(track)});
  return files;
}

}  // namespace

const std::vector<FormatInfo>& Formats() {
  static const std::vector<FormatInfo> formats = {
      {Format::kQgcPlan, "qgc-plan", "mission.plan", "QGroundControl .plan (JSON) for PX4 or ArduPilot", true,
       &StraightTrackingCamera, MavlinkLimits(), &WriteMavlink<&QgcPlanText>},
      {Format::kQgcWpl, "qgc-wpl", "mission.waypoints", "QGC WPL 110 plain-text waypoints (Mission Planner)", true,
       &StraightTrackingCamera, MavlinkLimits(), &WriteMavlink<&QgcWplText>},
      {Format::kMavlinkBin, "mavlink-bin", "mission.mavlink",
       "MAVLink 2 MISSION_ITEM_INT frames, as a ground station uploads them", true, &StraightTrackingCamera,
       MavlinkLimits(), &WriteMavlink<&MavlinkBinBytes>},
      {Format::kDjiWpml, "dji-wpml", "mission.kmz", "DJI WPML KMZ (DJI Pilot 2, FlightHub 2, MSDK v5)", false,
       &CoordinatedTurnsTrackingHeading, WpmlLimits(), &WriteWpml},
      {Format::kDjiMsdkJson, "dji-msdk-json", "mission.dji.json", "DJI Mobile SDK v4 WaypointMission as JSON", false,
       &StraightWithHeadings, MsdkLimits(), &WriteMsdk},
      {Format::kLitchiCsv, "litchi-csv", "mission.litchi.csv", "Litchi Mission Hub CSV", false, &StraightTrackingCamera,
       LitchiLimits(), &WriteLitchi},
      {Format::kGltfCamera, "gltf-camera", "previs.glb",
       "glTF 2.0 binary: a camera per drone animated at every sample, with --scene the scene's mesh (Blender, "
       "engines, three.js)",
       false, nullptr, FormatLimits(), nullptr, FormatKind::kCameraTrack, &WriteGltfCameraFile},
      {Format::kNukeChan, "nuke-chan", "<drone>.chan",
       "Nuke .chan camera track per drone: frame, translation, ZXY rotation, vertical field of view (Nuke, "
       "Blender)",
       false, nullptr, FormatLimits(), nullptr, FormatKind::kCameraTrack, &WriteNukeChanFiles},
  };
  return formats;
}

const FormatInfo& InfoOf(Format format) {
  for (const FormatInfo& f : Formats()) {
    if (f.format == format) return f;
  }
  CINEPATH_CHECK(false);
  return Formats().front();
}

const char* FormatName(Format format) { return InfoOf(format).name; }
const char* FormatFileName(Format format) { return InfoOf(format).file_name; }
bool IsMavlinkFormat(Format format) { return InfoOf(format).mavlink; }
bool IsCameraTrackFormat(Format format) { return InfoOf(format).kind == FormatKind::kCameraTrack; }
FormatLimits LimitsOf(Format format) { return InfoOf(format).limits; }

Format ParseFormat(const std::string& name) {
  std::string known;
  for (const FormatInfo& f : Formats()) {
    if (name == f.name) return f.format;
    known += known.empty() ? f.name : std::string(", ") + f.name;
  }
  throw InputError("formats: unknown format '" + name + "' (known: " + known + ")");
}

}  // namespace cinepath::exporter
