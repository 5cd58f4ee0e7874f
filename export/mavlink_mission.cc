#include "export/mavlink_mission.h"

#include <cmath>

#include <fmt/format.h>

#include "core/angles.h"
#include "core/error.h"

namespace cinepath::exporter {

namespace {

MavItem DoItem(int command, std::array<double, 7> params, int waypoint) {
  MavItem item;
  item.command = command;
  item.frame = mav::kFrameMission;
  item.params = params;
  item.waypoint = waypoint;
  return item;
}

bool Changed(double a, double b, double tolerance) { return std::abs(a - b) > tolerance; }

}  // namespace

MavItem HomeItem(const Mission& mission) {
  MavItem home;
  home.command = mav::kNavWaypoint;
  home.frame = mav::kFrameGlobal;
  home.params = {0, 0, 0, 0, mission.home.lat_deg, mission.home.lon_deg, mission.home.amsl_m};
  return home;
}

namespace {

// Where a point of interest starts, ends and governs the leg out of waypoint `w` (docs/mission-formats.md):
// PX4 runs a waypoint's block after reaching it, ArduPilot while flying to it.
struct RoiAtWaypoint {
  bool starts = false, ends = false, governs = false;
  const MissionRoi* governing = nullptr;
};

RoiAtWaypoint RoiAt(const Mission& mission, size_t w, bool px4) {
  const auto& wps = mission.waypoints;
  const MissionWaypoint& wp = wps[w];
  const MissionWaypoint* prev = w > 0 ? &wps[w - 1] : nullptr;
  const int wi = static_cast<int>(w);
  // Point of interest. PX4 runs this block after reaching wp: the ROI governs the legs that leave
  // waypoints first..last−1. ArduPilot runs it while flying to wp: it governs the leg prev→wp.
  const MissionRoi* roi = wp.roi >= 0 ? &mission.rois[wp.roi] : nullptr;
  const MissionRoi* prev_roi = prev && prev->roi >= 0 ? &mission.rois[prev->roi] : nullptr;
  RoiAtWaypoint at;
  if (px4) {
    at.starts = roi && wi == roi->first_waypoint;
    at.ends = roi && wi == roi->last_waypoint;
    at.governs = roi && wi < roi->last_waypoint;
  } else {
    at.starts = prev_roi && static_cast<int>(w) - 1 == prev_roi->first_waypoint;
    at.ends = prev_roi && static_cast<int>(w) - 1 == prev_roi->last_waypoint;
    at.governs = prev_roi && static_cast<int>(w) - 1 < prev_roi->last_waypoint;
  }
  at.governing = px4 ? roi : prev_roi;
  return at;
}

// DO_SET_ROI_NONE where a stretch ends, DO_SET_ROI_LOCATION where one starts.
void AddRoiItems(const RoiAtWaypoint& at, AltitudeRef ref, int nav_frame, int wi, MavMission& out) {
  const MissionRoi* governing = at.governing;
  if (at.ends) out.items.push_back(DoItem(mav::kDoSetRoiNone, {0, 0, 0, 0, 0, 0, 0}, wi));
  if (at.starts) {
    MavItem set_roi;
    set_roi.command = mav::kDoSetRoiLocation;
    set_roi.frame = nav_frame;
    set_roi.params = {0,
                      0,
                      0,
                      0,
                      governing->lat_deg,
                      governing->lon_deg,
                      ref == AltitudeRef::kRelative ? governing->relative_alt_m : governing->amsl_m};
    set_roi.waypoint = wi;
    out.items.push_back(set_roi);
  }
}

// Outside a point of interest: the heading (ArduPilot only) and the gimbal's two angles.
void AddPointingItems(const MissionWaypoint& wp, double heading, bool px4, int wi, MavMission& out) {
  if (!px4) {
    // ArduCopter drops NAV_WAYPOINT param4: absolute yaw, default rate, shortest way.
    out.items.push_back(DoItem(mav::kConditionYaw, {heading, 0, 0, 0, 0, 0, 0}, wi));
  }
  // Gimbal: both angles (ArduPilot needs both), yaw relative to the vehicle (flags 0 = follow).
  out.items.push_back(DoItem(mav::kDoGimbalManagerPitchYaw,
                             {wp.gimbal_pitch_deg, NormalizeDeg180(wp.gimbal_yaw_deg), 0, 0, 0, 0, 0}, wi));
}

// The lens: zoom where the focal length changes, focus (PX4) and aperture (ArduPilot) where they change.
void AddLensItems(const Mission& mission, const MissionWaypoint& wp, const MissionWaypoint* prev, bool px4, int wi,
                  MavMission& out) {
  const bool has_zoom = mission.max_focal_length_mm > mission.min_focal_length_mm;
  if (!prev || Changed(prev->focal_length_mm, wp.focal_length_mm, 0.05)) {
    if (px4) {
      out.items.push_back(
          DoItem(mav::kSetCameraZoom, {mav::kZoomTypeFocalLength, wp.focal_length_mm, 0, 0, 0, 0, 0}, wi));
    } else if (has_zoom || !prev) {
      out.items.push_back(DoItem(mav::kSetCameraZoom,
                                 {mav::kZoomTypeRange, ZoomPercent(mission, wp.focal_length_mm), 0, 0, 0, 0, 0}, wi));
    }
  }
  const bool focus_changed =
      !prev || (std::isinf(prev->focus_distance_m) != std::isinf(wp.focus_distance_m)) ||
      (!std::isinf(wp.focus_distance_m) && Changed(prev->focus_distance_m, wp.focus_distance_m, 0.01));
  if (px4 && focus_changed) {
    if (std::isinf(wp.focus_distance_m)) {
      // No "infinity" in METERS: the far end of the focus range.
      out.items.push_back(DoItem(mav::kSetCameraFocus, {mav::kFocusTypeRange, 100, 0, 0, 0, 0, 0}, wi));
    } else {
      out.items.push_back(
          DoItem(mav::kSetCameraFocus, {mav::kFocusTypeMeters, wp.focus_distance_m, 0, 0, 0, 0, 0}, wi));
    }
  }
  if (!px4 && (!prev || Changed(prev->f_number, wp.f_number, 0.01))) {
    out.items.push_back(DoItem(mav::kDoDigicamConfigure, {0, 0, wp.f_number, 0, 0, 0, 0}, wi));
  }
}

// Recording. PX4 runs DO items once the waypoint before them is reached: start/stop right after
// the waypoint that carries the flag. ArduPilot runs them while flying to the NAV item before
// them: a flag of waypoint w−1 goes into waypoint w's block (the final stop follows RTL).
void AddRecordItems(const MissionWaypoint& wp, const MissionWaypoint* prev, bool px4, bool last, int wi,
                    MavMission& out) {
  if (px4) {
    if (wp.record_start) out.items.push_back(DoItem(mav::kVideoStartCapture, {0, 0, 0, 0, 0, 0, 0}, wi));
    if (wp.record_stop && !last) {
      out.items.push_back(DoItem(mav::kVideoStopCapture, {0, 0, 0, 0, 0, 0, 0}, wi));
    }
  } else if (prev) {
    if (prev->record_start) out.items.push_back(DoItem(mav::kVideoStartCapture, {0, 0, 0, 0, 0, 0, 0}, wi));
    if (prev->record_stop) out.items.push_back(DoItem(mav::kVideoStopCapture, {0, 0, 0, 0, 0, 0, 0}, wi));
  }
}

// Speed of a leg: PX4 runs DO items once the waypoint before them is reached, so the leg w→w+1 gets
// its speed in waypoint w's block; ArduPilot runs DO items while flying towards the NAV item before
// them, so the leg w−1→w gets its speed in waypoint w's block.
void AddSpeedItems(const std::vector<MissionWaypoint>& wps, size_t w, bool px4, MavMission& out) {
  const MissionWaypoint& wp = wps[w];
  const MissionWaypoint* prev = w > 0 ? &wps[w - 1] : nullptr;
  const int wi = static_cast<int>(w);
  if (px4 && w + 1 < wps.size() && (!prev || Changed(prev->speed_mps, wp.speed_mps, 0.01))) {
    out.items.push_back(DoItem(mav::kDoChangeSpeed, {mav::kSpeedTypeGround, wp.speed_mps, -1, 0, 0, 0, 0}, wi));
  }
  if (!px4 && prev) {
    const MissionWaypoint* before = w >= 2 ? &wps[w - 2] : nullptr;
    if (!before || Changed(before->speed_mps, prev->speed_mps, 0.01)) {
      out.items.push_back(DoItem(mav::kDoChangeSpeed, {mav::kSpeedTypeGround, prev->speed_mps, -1, 0, 0, 0, 0}, wi));
    }
  }
}

// After the last waypoint: return to launch, and the last stop of recording (and of a point of interest).
void AddEnding(const Mission& mission, bool px4, MavMission& out) {
  const auto& wps = mission.waypoints;
  const int last = static_cast<int>(wps.size()) - 1;
  if (px4) {
    out.items.push_back(DoItem(mav::kVideoStopCapture, {0, 0, 0, 0, 0, 0, 0}, last));
    out.items.push_back(DoItem(mav::kNavReturnToLaunch, {0, 0, 0, 0, 0, 0, 0}, -1));
  } else {
    out.items.push_back(DoItem(mav::kNavReturnToLaunch, {0, 0, 0, 0, 0, 0, 0}, -1));
    // A stretch that ends at the last waypoint: its ROI_NONE runs when RTL starts.
    if (wps.back().roi >= 0 && mission.rois[wps.back().roi].last_waypoint == last) {
      out.items.push_back(DoItem(mav::kDoSetRoiNone, {0, 0, 0, 0, 0, 0, 0}, last));
    }
    if (wps.back().record_start) out.items.push_back(DoItem(mav::kVideoStartCapture, {0, 0, 0, 0, 0, 0, 0}, last));
    out.items.push_back(DoItem(mav::kVideoStopCapture, {0, 0, 0, 0, 0, 0, 0}, last));
  }
}

// What the mission could not carry, and how points of interest are flown, for the report.
void AddNotes(const Mission& mission, bool px4, MavMission& out) {
  const bool has_zoom = mission.max_focal_length_mm > mission.min_focal_length_mm;
  if (!mission.rois.empty()) {
    out.notes.push_back(fmt::format(
        "{} point(s) of interest: DO_SET_ROI_LOCATION / DO_SET_ROI_NONE; inside them the firmware points the camera "
        "({}), per-waypoint {}gimbal items left out",
        mission.rois.size(),
        px4 ? "PX4: nose and gimbal to the ROI"
            : "ArduPilot: mount to the ROI, vehicle yaws if "
              "the mount cannot pan",
        px4 ? "" : "CONDITION_YAW and "));
  }
  if (px4) {
    out.notes.push_back("aperture (f-number) not carried: PX4 rejects DO_DIGICAM_CONFIGURE in missions");
  } else {
    out.notes.push_back("focus distance not carried: ArduPilot's SET_CAMERA_FOCUS takes no metres");
    if (!has_zoom) {
      out.notes.push_back("zoom: the plan's camera is a prime lens (min = max focal length); zoom set to 0 %");
    }
  }
}

}  // namespace

MavMission BuildMavMission(const Mission& mission, Firmware firmware, AltitudeRef ref) {
  if (ref == AltitudeRef::kEllipsoid) {
    throw InputError(
        "altitude_ref ellipsoid: MAVLink missions carry altitudes relative to home (frame 3) or "
        "AMSL (frame 0), not ellipsoidal heights");
  }
  CINEPATH_CHECK(!mission.waypoints.empty());
  const bool px4 = firmware == Firmware::kPx4;
  const int nav_frame = ref == AltitudeRef::kRelative ? mav::kFrameGlobalRelativeAlt : mav::kFrameGlobal;
  MavMission out;
  const auto& wps = mission.waypoints;
  const MissionWaypoint& first = wps.front();

  MavItem takeoff;
  takeoff.command = mav::kNavTakeoff;
  takeoff.frame = nav_frame;
  takeoff.params = {0,
                    0,
                    0,
                    px4 ? NormalizeDeg360(first.heading_deg) : 0.0,
                    mission.home.lat_deg,
                    mission.home.lon_deg,
                    AltitudeIn(first, ref)};
  out.items.push_back(takeoff);

  for (size_t w = 0; w < wps.size(); ++w) {
    const MissionWaypoint& wp = wps[w];
    const int wi = static_cast<int>(w);
    const double heading = NormalizeDeg360(wp.heading_deg);
    const RoiAtWaypoint roi = RoiAt(mission, w, px4);

    MavItem nav;
    nav.command = mav::kNavWaypoint;
    nav.frame = nav_frame;
    nav.params = {0, 0, 0, px4 ? heading : 0.0, wp.lat_deg, wp.lon_deg, AltitudeIn(wp, ref)};
    nav.waypoint = wi;
    out.items.push_back(nav);

    AddRoiItems(roi, ref, nav_frame, wi, out);
    if (!roi.governs) AddPointingItems(wp, heading, px4, wi, out);
    const MissionWaypoint* prev = w > 0 ? &wps[w - 1] : nullptr;
    AddLensItems(mission, wp, prev, px4, wi, out);
    AddRecordItems(wp, prev, px4, w + 1 == wps.size(), wi, out);
    AddSpeedItems(wps, w, px4, out);
  }
  AddEnding(mission, px4, out);
  AddNotes(mission, px4, out);
  return out;
}

}  // namespace cinepath::exporter
