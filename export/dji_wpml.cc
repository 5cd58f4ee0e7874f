#include "export/dji_wpml.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/angles.h"
#include "core/number_format.h"
#include "export/zip_writer.h"

namespace cinepath::exporter {

namespace {

constexpr double kMinSpeed = 1;
constexpr double kMaxSpeed = 15;

// A tiny indenting XML text builder (values here never need escaping: numbers and fixed words).
class Xml {
 public:
  void Open(const std::string& tag) {
    Indent();
    text_ += "<" + tag + ">\n";
    ++depth_;
  }
  void Close(const std::string& tag) {
    --depth_;
    Indent();
    text_ += "</" + tag + ">\n";
  }
  void Leaf(const std::string& tag, const std::string& value) {
    Indent();
    text_ += "<" + tag + ">" + value + "</" + tag + ">\n";
  }
  void Raw(const std::string& line) {
    Indent();
    text_ += line + "\n";
  }
  std::string& text() { return text_; }

 private:
  void Indent() { text_.append(2 * depth_, ' '); }
  std::string text_;
  int depth_ = 0;
};

std::string Num(double v, int decimals) { return FormatFixed(v, decimals); }
std::string Int(int v) { return std::to_string(v); }
double ClampSpeed(double v) { return std::clamp(v, kMinSpeed, kMaxSpeed); }

// Hover time at the end of the leg a→b when the leg is slower than kMinSpeed (0 otherwise; hovers
// shorter than 0.05 s are dropped).
double SlowLegHoverS(const MissionWaypoint& a, const MissionWaypoint& b) {
  if (a.speed_mps >= kMinSpeed || a.transit_after) return 0;
  const double length_m = (b.position_enu_m - a.position_enu_m).norm();
  const double hover_s = (b.time_s - a.time_s) - length_m / kMinSpeed;
  return hover_s >= 0.05 ? hover_s : 0;
}

void MissionConfig(Xml& x, const Mission& mission, const DroneProfile& profile, bool is_template) {
  double max_rel = 0;
  for (const auto& wp : mission.waypoints) max_rel = std::max(max_rel, wp.relative_alt_m);
  const double rth = std::clamp(std::ceil(max_rel + 10.0), 2.0, 1500.0);
  x.Open("wpml:missionConfig");
  x.Leaf("wpml:flyToWaylineMode", "safely");
  x.Leaf("wpml:finishAction", "goHome");
  x.Leaf("wpml:exitOnRCLost", "executeLostAction");
  x.Leaf("wpml:executeRCLostAction", "goBack");
  x.Leaf("wpml:takeOffSecurityHeight",
         Num(std::clamp(std::ceil(mission.waypoints.front().relative_alt_m), 8.0, 1500.0), 1));
  x.Leaf("wpml:globalTransitionalSpeed", Num(ClampSpeed(mission.waypoints.front().speed_mps), 2));
  x.Leaf("wpml:globalRTHHeight", Num(rth, 1));
  if (is_template) {
    x.Leaf("wpml:takeOffRefPoint", Num(mission.home.lat_deg, 9) + "," + Num(mission.home.lon_deg, 9) + "," +
                                       Num(mission.home.ellipsoidal_height_m, 3));
  }
  x.Open("wpml:droneInfo");
  x.Leaf("wpml:droneEnumValue", Int(profile.dji_drone_enum));
  x.Leaf("wpml:droneSubEnumValue", Int(profile.dji_drone_sub_enum));
  x.Close("wpml:droneInfo");
  x.Open("wpml:payloadInfo");
  x.Leaf("wpml:payloadEnumValue", Int(profile.dji_payload_enum));
  x.Leaf("wpml:payloadPositionIndex", "0");
  x.Close("wpml:payloadInfo");
  x.Close("wpml:missionConfig");
}

// The point of interest governing the leg that leaves waypoint w (nullptr: none).
const MissionRoi* LegRoi(const Mission& mission, size_t w) {
  const MissionWaypoint& wp = mission.waypoints[w];
  if (mission.roi_tracking == RoiTracking::kNone || wp.roi < 0) return nullptr;
  const MissionRoi& roi = mission.rois[wp.roi];
  return static_cast<int>(w) < roi.last_waypoint ? &roi : nullptr;
}

// Heading of the leg leaving the waypoint: towards the point of interest inside a stretch (DJI turns
// the nose only, "Z not supported"), else smoothTransition to the next waypoint's heading.
void HeadingParam(Xml& x, const Mission& mission, size_t w, bool relative) {
  const MissionWaypoint& wp = mission.waypoints[w];
  const MissionRoi* roi = LegRoi(mission, w);
  x.Open("wpml:waypointHeadingParam");
  x.Leaf("wpml:waypointHeadingMode", roi ? "towardPOI" : "smoothTransition");
  x.Leaf("wpml:waypointHeadingAngle", Num(NormalizeDeg180(wp.heading_deg), 2));
  x.Leaf("wpml:waypointPoiPoint", roi ? Num(roi->lat_deg, 9) + "," + Num(roi->lon_deg, 9) + "," +
                                            Num(relative ? roi->relative_alt_m : roi->ellipsoidal_height_m, 3)
                                      : "0.000000,0.000000,0.000000");
  x.Leaf("wpml:waypointHeadingPathMode", "followBadArc");
  x.Close("wpml:waypointHeadingParam");
}

// Coordinated turn with the fitted damping distance (dji_turns.h), or stop at the waypoint.
void TurnParam(Xml& x, const MissionWaypoint& wp) {
  x.Open("wpml:waypointTurnParam");
  if (wp.turn_damping_m > 0) {
    x.Leaf("wpml:waypointTurnMode", "coordinateTurn");
    x.Leaf("wpml:waypointTurnDampingDist", Num(wp.turn_damping_m, 2));
  } else {
    x.Leaf("wpml:waypointTurnMode", "toPointAndStopWithDiscontinuityCurvature");
  }
  x.Close("wpml:waypointTurnParam");
}

struct Action {
  std::string func;
  std::vector<std::pair<std::string, std::string>> params;
};

void ActionGroup(Xml& x, int& group_id, int start, int end, const std::string& trigger,
                 const std::vector<Action>& actions) {
  if (actions.empty()) return;
  x.Open("wpml:actionGroup");
  x.Leaf("wpml:actionGroupId", Int(group_id++));
  x.Leaf("wpml:actionGroupStartIndex", Int(start));
  x.Leaf("wpml:actionGroupEndIndex", Int(end));
  x.Leaf("wpml:actionGroupMode", "sequence");
  x.Open("wpml:actionTrigger");
  x.Leaf("wpml:actionTriggerType", trigger);
  x.Close("wpml:actionTrigger");
  for (size_t a = 0; a < actions.size(); ++a) {
    x.Open("wpml:action");
    x.Leaf("wpml:actionId", Int(static_cast<int>(a)));
    x.Leaf("wpml:actionActuatorFunc", actions[a].func);
    x.Open("wpml:actionActuatorFuncParam");
    for (const auto& [k, v] : actions[a].params) x.Leaf("wpml:" + k, v);
    x.Close("wpml:actionActuatorFuncParam");
    x.Close("wpml:action");
  }
  x.Close("wpml:actionGroup");
}

// Action groups of waypoint w: what happens on reaching it, and the gimbal sweep of the leg after it.
void WaypointActions(Xml& x, const Mission& mission, size_t w, int& group_id) {
  const auto& wps = mission.waypoints;
  const MissionWaypoint& wp = wps[w];
  std::vector<Action> reach;
  if (w == 0) {
    reach.push_back({"gimbalRotate",
                     {{"gimbalHeadingYawBase", "north"},
                      {"gimbalRotateMode", "absoluteAngle"},
                      {"gimbalPitchRotateEnable", "1"},
                      {"gimbalPitchRotateAngle", Num(wp.gimbal_pitch_deg, 2)},
                      {"gimbalRollRotateEnable", "0"},
                      {"gimbalRollRotateAngle", "0"},
                      {"gimbalYawRotateEnable", "1"},
                      {"gimbalYawRotateAngle", Num(NormalizeDeg180(wp.heading_deg + wp.gimbal_yaw_deg), 2)},
                      {"gimbalRotateTimeEnable", "0"},
                      {"gimbalRotateTime", "0"},
                      {"payloadPositionIndex", "0"}}});
  }
  if (w == 0 || std::abs(wps[w - 1].focal_length_mm - wp.focal_length_mm) > 0.05) {
    reach.push_back({"zoom",
                     {{"payloadPositionIndex", "0"},
                      {"focalLength", Num(FocalLength35mmEquivalent(mission, wp.focal_length_mm), 1)}}});
  }
  if (wp.record_start) {
    reach.push_back({"startRecord", {{"payloadPositionIndex", "0"}, {"useGlobalPayloadLensIndex", "1"}}});
  }
  if (w > 0) {
    // A leg slower than WPML's 1 m/s minimum is flown at 1 m/s; the time left over is spent hovering
    // on arrival, so the waypoint times of the plan are kept.
    const double hover_s = SlowLegHoverS(wps[w - 1], wp);
    if (hover_s > 0) reach.push_back({"hover", {{"hoverTime", Num(hover_s, 2)}}});
  }
  if (wp.record_stop) reach.push_back({"stopRecord", {{"payloadPositionIndex", "0"}}});
  const int index = static_cast<int>(w);
  ActionGroup(x, group_id, index, index, "reachPoint", reach);
  if (w + 1 < wps.size()) {
    ActionGroup(x, group_id, index, index + 1, "betweenAdjacentPoints",
                {{"gimbalEvenlyRotate",
                  {{"gimbalPitchRotateAngle", Num(wps[w + 1].gimbal_pitch_deg, 2)}, {"payloadPositionIndex", "0"}}}});
  }
}

// One Placemark per waypoint. template.kml states every setting per point (with the useGlobal* flags
// off); waylines.wpml carries what the aircraft executes (the height in its execute mode).
enum class WpmlFile { kTemplate, kWaylines };

void Placemarks(Xml& x, const Mission& mission, bool relative, WpmlFile file) {
  const bool tmpl = file == WpmlFile::kTemplate;
  int group_id = 0;
  for (size_t w = 0; w < mission.waypoints.size(); ++w) {
    const MissionWaypoint& wp = mission.waypoints[w];
    x.Open("Placemark");
    x.Open("Point");
    x.Leaf("coordinates", Num(wp.lon_deg, 9) + "," + Num(wp.lat_deg, 9));
    x.Close("Point");
    x.Leaf("wpml:index", Int(static_cast<int>(w)));
    if (tmpl) {
      x.Leaf("wpml:useGlobalHeight", "0");
      x.Leaf("wpml:ellipsoidHeight", Num(wp.ellipsoidal_height_m, 3));
      x.Leaf("wpml:height", Num(relative ? wp.relative_alt_m : wp.amsl_m, 3));
      x.Leaf("wpml:useGlobalSpeed", "0");
    } else {
      x.Leaf("wpml:executeHeight", Num(relative ? wp.relative_alt_m : wp.ellipsoidal_height_m, 3));
    }
    x.Leaf("wpml:waypointSpeed", Num(ClampSpeed(wp.speed_mps), 2));
    if (tmpl) x.Leaf("wpml:useGlobalHeadingParam", "0");
    HeadingParam(x, mission, w, relative);
    if (tmpl) x.Leaf("wpml:useGlobalTurnParam", "0");
    TurnParam(x, wp);
    x.Leaf("wpml:useStraightLine", "1");
    if (tmpl) {
      x.Leaf("wpml:gimbalPitchAngle", Num(wp.gimbal_pitch_deg, 2));
      x.Leaf("wpml:isRisky", "0");
    }
    WaypointActions(x, mission, w, group_id);
    x.Close("Placemark");
  }
}

const char* kHeader =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<kml xmlns=\"http://www.opengis.net/kml/2.2\" xmlns:wpml=\"http://www.dji.com/wpmz/1.0.2\">\n";

}  // namespace

WpmlDocuments WriteWpmlDocuments(const Mission& mission, const DroneProfile& profile, AltitudeRef ref) {
  const bool relative = ref == AltitudeRef::kRelative;
  const auto& wps = mission.waypoints;
  const double auto_speed = ClampSpeed(wps.front().speed_mps);
  WpmlDocuments docs;

  // template.kml
  {
    Xml x;
    x.text() = kHeader;
    x.Open("Document");
    x.Leaf("wpml:author", "cinepath");
    MissionConfig(x, mission, profile, true);
    x.Open("Folder");
    x.Leaf("wpml:templateType", "waypoint");
    x.Leaf("wpml:templateId", "0");
    x.Open("wpml:waylineCoordinateSysParam");
    x.Leaf("wpml:coordinateMode", "WGS84");
    x.Leaf("wpml:heightMode", relative ? "relativeToStartPoint" : "EGM96");
    x.Close("wpml:waylineCoordinateSysParam");
    x.Leaf("wpml:autoFlightSpeed", Num(auto_speed, 2));
    x.Leaf("wpml:globalHeight", Num(relative ? wps.front().relative_alt_m : wps.front().amsl_m, 3));
    x.Leaf("wpml:gimbalPitchMode", "usePointSetting");
    x.Open("wpml:globalWaypointHeadingParam");
    x.Leaf("wpml:waypointHeadingMode", "smoothTransition");
    x.Leaf("wpml:waypointHeadingAngle", Num(NormalizeDeg180(wps.front().heading_deg), 2));
    x.Leaf("wpml:waypointPoiPoint", "0.000000,0.000000,0.000000");
    x.Leaf("wpml:waypointHeadingPathMode", "followBadArc");
    x.Close("wpml:globalWaypointHeadingParam");
    x.Leaf("wpml:globalWaypointTurnMode", "toPointAndStopWithDiscontinuityCurvature");
    x.Leaf("wpml:globalUseStraightLine", "1");
    Placemarks(x, mission, relative, WpmlFile::kTemplate);
    x.Close("Folder");
    x.Close("Document");
    x.text() += "</kml>\n";
    docs.template_kml = std::move(x.text());
  }

  // waylines.wpml
  {
    Xml x;
    x.text() = kHeader;
    x.Open("Document");
    MissionConfig(x, mission, profile, false);
    x.Open("Folder");
    x.Leaf("wpml:templateId", "0");
    x.Leaf("wpml:executeHeightMode", relative ? "relativeToStartPoint" : "WGS84");
    x.Leaf("wpml:waylineId", "0");
    x.Leaf("wpml:autoFlightSpeed", Num(auto_speed, 2));
    Placemarks(x, mission, relative, WpmlFile::kWaylines);
    x.Close("Folder");
    x.Close("Document");
    x.text() += "</kml>\n";
    docs.waylines_wpml = std::move(x.text());
  }

  docs.notes.push_back("focus distance not carried: WPML's focus action has no distance field");
  docs.notes.push_back("aperture (f-number) not carried: WPML has no aperture action");
  docs.notes.push_back("zoom written as the 35 mm-equivalent focal length (DJI's focalLength reference is UNVERIFIED)");
  int turns = 0;
  double min_d = 0, max_d = 0;
  for (const auto& wp : wps) {
    if (wp.turn_damping_m <= 0) continue;
    min_d = turns == 0 ? wp.turn_damping_m : std::min(min_d, wp.turn_damping_m);
    max_d = std::max(max_d, wp.turn_damping_m);
    ++turns;
  }
  docs.notes.push_back(fmt::format(
      "coordinated turns at {} of {} waypoints (damping {:.2f}-{:.2f} m), the others stop; modelled path deviation "
      "{:.3f} m ({:.3f} m as straight legs)",
      turns, wps.size(), min_d, max_d, mission.max_deviation_reached_m, mission.straight_deviation_reached_m));
  if (!mission.rois.empty() && mission.roi_tracking != RoiTracking::kNone) {
    docs.notes.push_back(fmt::format(
        "{} point(s) of interest: heading towardPOI on their legs (DJI turns the nose only; gimbal pitch still "
        "interpolated per leg)",
        mission.rois.size()));
  }
  int slow_legs = 0;
  double hover_total_s = 0;
  for (size_t w = 1; w < wps.size(); ++w) {
    const double hover_s = SlowLegHoverS(wps[w - 1], wps[w]);
    slow_legs += hover_s > 0;
    hover_total_s += hover_s;
  }
  if (slow_legs > 0) {
    docs.notes.push_back(fmt::format(
        "{} leg(s) slower than WPML's 1 m/s minimum: flown at 1 m/s, then a hover of {:.2f} s in total on arrival "
        "(waypoint times kept; the slow motion itself is not)",
        slow_legs, hover_total_s));
  }
  bool gimbal_yaw_varies = false;
  for (const auto& wp : wps)
    gimbal_yaw_varies |= std::abs(AngleDiffDeg(wps.front().gimbal_yaw_deg, wp.gimbal_yaw_deg)) > 0.5;
  if (gimbal_yaw_varies) {
    docs.notes.push_back("gimbal yaw set only at the first waypoint; afterwards the gimbal follows the heading");
  }
  return docs;
}

std::string WriteDjiKmz(const WpmlDocuments& documents) {
  ZipWriter zip;
  zip.Add("wpmz/template.kml", documents.template_kml);
  zip.Add("wpmz/waylines.wpml", documents.waylines_wpml);
  return zip.Finish();
}

}  // namespace cinepath::exporter
