#include "export/dji_msdk_json.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/json.h"

namespace cinepath::exporter {

MsdkJson WriteDjiMsdkJson(const Mission& mission) {
  const auto& wps = mission.waypoints;
  double max_speed = 0;
  for (const auto& wp : wps) max_speed = std::max(max_speed, wp.speed_mps);
  Json j;
  j["format"] = "cinepath-dji-msdk-v4-waypoint-mission";
  j["version"] = 1;
  j["altitudeReference"] = "relativeToTakeoff";
  j["missionID"] = 0;
  j["maxFlightSpeed"] = RoundToDecimals(std::clamp(max_speed, 2.0, 15.0), 2);
  j["autoFlightSpeed"] = RoundToDecimals(std::clamp(wps.front().speed_mps, 0.0, 15.0), 2);
  j["finishedAction"] = "GO_HOME";
  j["headingMode"] = "USING_WAYPOINT_HEADING";
  j["flightPathMode"] = "NORMAL";
  j["gotoFirstWaypointMode"] = "SAFELY";
  j["exitMissionOnRCSignalLostEnabled"] = false;
  j["gimbalPitchRotationEnabled"] = true;
  j["repeatTimes"] = 1;
  j["pointOfInterest"] = nullptr;
  j["home"] = Json{{"latitude", mission.home.lat_deg},
                   {"longitude", mission.home.lon_deg},
                   {"altitudeAmsl", RoundToDecimals(mission.home.amsl_m, 3)}};
  Json list = Json::array();
  bool held_too_long = false;
  for (size_t w = 0; w < wps.size(); ++w) {
    const MissionWaypoint& wp = wps[w];
    Json actions = Json::array();
    if (wp.record_start) actions.push_back(Json{{"type", "START_RECORD"}, {"param", 0}});
    // A hold is a series of STAY actions (param in ms, int16: at most 32767 each).
    int hold_ms = static_cast<int>(std::lround(wp.hold_s * 1000));
    while (hold_ms > 0 && actions.size() < 14) {
      const int chunk = std::min(hold_ms, 32767);
      actions.push_back(Json{{"type", "STAY"}, {"param", chunk}});
      hold_ms -= chunk;
    }
    if (hold_ms > 0) held_too_long = true;
    if (wp.record_stop) actions.push_back(Json{{"type", "STOP_RECORD"}, {"param", 0}});
    Json p;
    p["latitude"] = RoundToDecimals(wp.lat_deg, 9);
    p["longitude"] = RoundToDecimals(wp.lon_deg, 9);
    p["altitude"] = RoundToDecimals(wp.relative_alt_m, 3);
    p["heading"] = RoundToDecimals(NormalizeDeg180(wp.heading_deg), 2);
    p["gimbalPitch"] = RoundToDecimals(std::clamp(wp.gimbal_pitch_deg, -90.0, 0.0), 2);
    p["speed"] = RoundToDecimals(std::clamp(wp.speed_mps, 0.0, 15.0), 2);
    p["turnMode"] = "CLOCKWISE";
    p["cornerRadiusInMeters"] = 0.2;
    p["shootPhotoTimeInterval"] = -1;
    p["shootPhotoDistanceInterval"] = -1;
    p["actionRepeatTimes"] = 1;
    p["actionTimeoutInSeconds"] = 60;
    p["actions"] = actions;
    list.push_back(p);
  }
  j["waypoints"] = list;

  MsdkJson out;
  out.text = DumpJson(j);
  if (held_too_long) out.notes.push_back("a hold longer than 13 STAY actions (425 s) was shortened");
  out.notes.push_back("zoom (focal length) not carried: MSDK v4 waypoints have no focal-length field");
  out.notes.push_back("focus distance not carried: MSDK v4 waypoints have no focus-distance field");
  out.notes.push_back("aperture (f-number) not carried: MSDK v4 waypoints have no aperture field");
  out.notes.push_back("gimbal yaw not carried: MSDK v4 waypoints set gimbal pitch only");
  return out;
}

}  // namespace cinepath::exporter
