#include "export/litchi_csv.h"

#include <algorithm>
#include <vector>

#include "core/angles.h"
#include "core/number_format.h"

namespace cinepath::exporter {

namespace {
constexpr int kActionSlots = 15;
}

LitchiCsv WriteLitchiCsv(const Mission& mission) {
  std::string out = "latitude,longitude,altitude(m),heading(deg),curvesize(m),rotationdir,gimbalmode,gimbalpitchangle";
  for (int a = 1; a <= kActionSlots; ++a) {
    out += ",actiontype" + std::to_string(a) + ",actionparam" + std::to_string(a);
  }
  out +=
      ",altitudemode,speed(m/s),poi_latitude,poi_longitude,poi_altitude(m),poi_altitudemode,photo_timeinterval,"
      "photo_distinterval\n";
  const auto& wps = mission.waypoints;
  for (size_t w = 0; w < wps.size(); ++w) {
    const MissionWaypoint& wp = wps[w];
    // Inside a point-of-interest stretch the waypoint is assigned the POI and the gimbal "focuses" it
    // (gimbal mode 1); elsewhere the gimbal pitch is interpolated (mode 2).
    const MissionRoi* roi = mission.roi_tracking != RoiTracking::kNone && wp.roi >= 0 ? &mission.rois[wp.roi] : nullptr;
    out += FormatFixed(wp.lat_deg, 9) + "," + FormatFixed(wp.lon_deg, 9) + "," + FormatFixed(wp.relative_alt_m, 3) +
           "," + FormatFixed(NormalizeDeg360(wp.heading_deg), 2) + ",0,0," + (roi ? "1," : "2,") +
           FormatFixed(wp.gimbal_pitch_deg, 2);
    std::vector<int> actions;
    if (wp.record_start) actions.push_back(2);  // start recording
    if (wp.record_stop) actions.push_back(3);   // stop recording
    for (int a = 0; a < kActionSlots; ++a) {
      out += a < static_cast<int>(actions.size()) ? "," + std::to_string(actions[a]) + ",0" : ",-1,0";
    }
    // Speed 0 means "mission cruise speed" in Litchi: never write 0 for a slow leg.
    out += ",0," + FormatFixed(std::clamp(wp.speed_mps, 0.1, 15.0), 2);
    out += roi ? "," + FormatFixed(roi->lat_deg, 9) + "," + FormatFixed(roi->lon_deg, 9) + "," +
                     FormatFixed(roi->relative_alt_m, 3) + ",0"
               : std::string(",0,0,0,0");
    out += ",-1,-1\n";
  }
  LitchiCsv csv;
  csv.text = std::move(out);
  if (!mission.rois.empty() && mission.roi_tracking != RoiTracking::kNone) {
    csv.notes.push_back(std::to_string(mission.rois.size()) +
                        " point(s) of interest: poi_* columns and gimbal mode 1 (focus POI) on their waypoints");
  }
  csv.notes.push_back("zoom (focal length) not carried: Litchi CSV has no focal-length column");
  csv.notes.push_back("focus distance not carried: Litchi CSV has no focus column");
  csv.notes.push_back("aperture (f-number) not carried: Litchi CSV has no aperture column");
  csv.notes.push_back("gimbal yaw not carried: Litchi CSV sets gimbal pitch only");
  return csv;
}

}  // namespace cinepath::exporter
