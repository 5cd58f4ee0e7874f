// A Mission as a list of MAVLink mission items for PX4 or ArduPilot (docs/mission-formats.md §3.1–3.5), shared by
// the .plan, WPL and binary writers.
//
// Per waypoint: NAV_WAYPOINT (frame 3 relative or 0 AMSL; yaw in param4 for PX4, CONDITION_YAW after
// it for ArduPilot, which ignores param4), DO_GIMBAL_MANAGER_PITCHYAW with both angles, SET_CAMERA_ZOOM
// (focal length for PX4, percent of the zoom range for ArduPilot), SET_CAMERA_FOCUS in metres (PX4;
// ArduPilot cannot), DO_DIGICAM_CONFIGURE for the aperture (ArduPilot; PX4 rejects it),
// DO_CHANGE_SPEED for the leg that follows. Camera items are emitted only when the value changes.
// The mission opens with NAV_TAKEOFF at home to the first waypoint's altitude and VIDEO_START_CAPTURE
// at the first waypoint, and closes with VIDEO_STOP_CAPTURE and RETURN_TO_LAUNCH (frame 2).
// No NaN is ever written: reserved params are 0, which both firmwares accept.
//
// Points of interest (Mission::rois): DO_SET_ROI_LOCATION (global frame, like the NAV items) where a
// stretch begins and DO_SET_ROI_NONE (frame 2) where it ends. While a ROI is active the firmware
// points the camera itself — PX4's navigator turns the nose to the ROI (overriding NAV_WAYPOINT
// param4) and its gimbal tracks it; ArduCopter sends the ROI to the mount and yaws the vehicle when
// the mount cannot pan — and a CONDITION_YAW or DO_GIMBAL_MANAGER_PITCHYAW would take that control
// back. So inside a stretch the per-waypoint CONDITION_YAW (ArduPilot) and gimbal items are left out;
// PX4's param4 keeps the plan heading (ignored while the ROI is active, harmless). Placement follows
// each firmware's DO-item timing (see recording): PX4 puts ROI in the first waypoint's block and
// ROI_NONE in the last one's (then the gimbal item of that waypoint); ArduPilot puts ROI in the block
// of the waypoint after the first and ROI_NONE in the block after the last (after RTL at the end).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "export/mission.h"
#include "export/platform.h"

namespace cinepath::exporter {

namespace mav {
// MAV_CMD
constexpr int kNavWaypoint = 16;
constexpr int kNavReturnToLaunch = 20;
constexpr int kNavTakeoff = 22;
constexpr int kConditionYaw = 115;
constexpr int kDoChangeSpeed = 178;
constexpr int kDoSetRoiLocation = 195;
constexpr int kDoSetRoiNone = 197;
constexpr int kDoDigicamConfigure = 202;
constexpr int kSetCameraZoom = 531;
constexpr int kSetCameraFocus = 532;
constexpr int kDoGimbalManagerPitchYaw = 1000;
constexpr int kVideoStartCapture = 2500;
constexpr int kVideoStopCapture = 2501;
// MAV_FRAME
constexpr int kFrameGlobal = 0;
constexpr int kFrameMission = 2;
constexpr int kFrameGlobalRelativeAlt = 3;
// MAV_AUTOPILOT (for .plan firmwareType)
constexpr int kAutopilotArduPilot = 3;
constexpr int kAutopilotPx4 = 12;
// Enums
constexpr int kZoomTypeRange = 2;
constexpr int kZoomTypeFocalLength = 3;
constexpr int kFocusTypeRange = 2;
constexpr int kFocusTypeMeters = 3;
constexpr int kSpeedTypeGround = 1;
}  // namespace mav

struct MavItem {
  int command = 0;
  int frame = mav::kFrameMission;
  std::array<double, 7> params{};  // param1..4, then x/lat, y/lon, z/alt (degrees, metres)
  bool autocontinue = true;
  int waypoint = -1;  // mission waypoint this item belongs to (−1: takeoff/RTL)
  bool IsGlobal() const { return frame == mav::kFrameGlobal || frame == mav::kFrameGlobalRelativeAlt; }
};

struct MavMission {
  std::vector<MavItem> items;      // mission items, without home
  std::vector<std::string> notes;  // what the firmware cannot carry
};

// `ref` must be kRelative or kAmsl (InputError otherwise: MAVLink has no ellipsoidal frame).
MavMission BuildMavMission(const Mission& mission, Firmware firmware, AltitudeRef ref);

// The home item (seq 0 in WPL and in ArduPilot uploads): NAV_WAYPOINT, frame 0, AMSL.
MavItem HomeItem(const Mission& mission);

}  // namespace cinepath::exporter
