#include "export/exporter.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"
#include "export/formats.h"

namespace cinepath::exporter {

void ExportOptions::Check() const {
  if (formats.empty()) throw InputError("formats: at least one format is required");
  for (size_t i = 0; i < formats.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (formats[i] == formats[j]) {
        throw InputError(std::string("formats: '") + FormatName(formats[i]) + "' given twice");
      }
    }
    const Format f = formats[i];
    if (IsMavlinkFormat(f) && altitude_ref == AltitudeRef::kEllipsoid) {
      throw InputError(std::string("altitude_ref ellipsoid: ") + FormatName(f) +
                       " carries altitudes relative to home or AMSL only (MAVLink frames 3 / 0)");
    }
    if ((f == Format::kDjiMsdkJson || f == Format::kLitchiCsv) && altitude_ref != AltitudeRef::kRelative) {
      throw InputError(std::string("altitude_ref ") + AltitudeRefName(altitude_ref) + ": " + FormatName(f) +
                       " carries altitudes relative to take-off only");
    }
  }
  build.selection.Check();
}

bool ExportResult::has_violations() const {
  for (const auto& r : reports) {
    if (!r.violations.empty()) return true;
  }
  return false;
}

Firmware FirmwareOf(const DroneProfile& profile) {
  return profile.firmware == "ardupilot" ? Firmware::kArduPilot : Firmware::kPx4;
}

ExportResult ExportMission(const Trajectory& trajectory, const ExportOptions& options) {
  options.Check();
  const DroneProfile& profile = options.build.drone ? *options.build.drone : trajectory.drone;
  const Firmware firmware = options.firmware.value_or(FirmwareOf(profile));
  const bool overridden = options.firmware && (profile.firmware == "px4" || profile.firmware == "ardupilot") &&
                          *options.firmware != FirmwareOf(profile);
  MissionBuildOptions build = options.build;
  build.absolute_altitudes = options.altitude_ref != AltitudeRef::kRelative;

  ExportResult result;
  // One Mission per flight model, in the order the formats ask for them (formats.h).
  const bool roi_auto = options.roi == RoiMode::kAuto;
  std::vector<FlightModel> models;
  std::vector<Format> formats;  // the missions (camera tracks are written by the caller, camera_track.h)
  for (Format format : options.formats) {
    if (!IsCameraTrackFormat(format)) formats.push_back(format);
  }
  if (formats.empty()) throw InputError("formats: no mission format (gltf-camera and nuke-chan are camera tracks)");
  for (Format format : formats) {
    const FlightModel model = InfoOf(format).flight_model(roi_auto);
    if (std::find(models.begin(), models.end(), model) != models.end()) continue;
    models.push_back(model);
    MissionBuildOptions b = build;
    b.selection.roi_tracking = model.roi_tracking;
    b.turn_model = model.turn_model;
    result.missions.push_back(BuildMission(trajectory, b));
  }
  const bool any_rois =
      std::any_of(result.missions.begin(), result.missions.end(), [](const Mission& m) { return !m.rois.empty(); });

  for (Format format : formats) {
    const FormatInfo& info = InfoOf(format);
    const FlightModel model = info.flight_model(roi_auto);
    const int mission_index = static_cast<int>(std::find(models.begin(), models.end(), model) - models.begin());
    const Mission& mission = result.missions[mission_index];
    FormatOutput written = info.write(
        {mission, firmware, options.altitude_ref, profile, any_rois && model.roi_tracking == RoiTracking::kNone});
    FormatReport report;
    report.mission = mission_index;
    report.format = format;
    report.file_name = info.file_name;
    report.notes = std::move(written.notes);
    if (overridden && info.mavlink) {
      report.notes.insert(report.notes.begin(),
                          fmt::format("--firmware {} overrides drone profile '{}', which flies {}",
                                      FirmwareName(firmware), profile.name, profile.firmware));
    }
    report.mission_items = written.mission_items;
    report.violations = ValidateMission(written.checked_mission ? *written.checked_mission : mission, format, profile,
                                        report.mission_items);
    result.files.push_back({report.file_name, std::move(written.contents)});
    result.reports.push_back(std::move(report));
  }
  result.mission = result.missions[result.reports.front().mission];
  result.drone_name = profile.name;
  result.firmware = firmware;

  if (result.has_violations() && !options.force) {
    std::string message = "the mission breaks platform limits (nothing written; --force writes it anyway):";
    int shown = 0;
    int total = 0;
    for (const auto& r : result.reports) {
      for (const auto& v : r.violations) {
        ++total;
        if (shown < 10) {
          message += "\n  " + v.message;
          ++shown;
        }
      }
    }
    if (total > shown) message += fmt::format("\n  ... and {} more", total - shown);
    throw InfeasibleError(message);
  }
  return result;
}

Json ReportJson(const ExportResult& result, const ExportOptions& options) {
  const Mission& m = result.mission;
  Json j;
  j["firmware"] = FirmwareName(result.firmware);
  j["drone"] = result.drone_name;
  j["altitude_ref"] = AltitudeRefName(options.altitude_ref);
  j["home"] = Json{{"lat_deg", m.home.lat_deg},
                   {"lon_deg", m.home.lon_deg},
                   {"amsl_m", RoundToDecimals(m.home.amsl_m, 3)},
                   {"ellipsoidal_height_m", RoundToDecimals(m.home.ellipsoidal_height_m, 3)}};
  j["plan_samples"] = m.plan_sample_count;
  j["waypoints"] = static_cast<int>(m.waypoints.size());
  j["max_deviation_m"] = options.build.selection.max_deviation_m;
  j["max_angle_deg"] = options.build.selection.max_angle_deg;
  j["deviation_reached_m"] = RoundToDecimals(m.max_deviation_reached_m, 4);
  j["angle_error_reached_deg"] = RoundToDecimals(m.max_angle_error_reached_deg, 4);
  j["cuts"] = m.cut_count;
  if (m.cut_count > 0) j["transit_speed_mps"] = m.transit_speed_mps;
  j["roi"] = options.roi == RoiMode::kAuto ? "auto" : "off";
  Json rois = Json::array();
  for (const Mission& mission : result.missions) {
    if (mission.roi_tracking == RoiTracking::kNone) continue;
    for (const MissionRoi& r : mission.rois) {
      rois.push_back(
          Json{{"start_time_s", RoundToDecimals(r.start_time_s, 3)},
               {"end_time_s", RoundToDecimals(r.end_time_s, 3)},
               {"lat_deg", RoundToDecimals(r.lat_deg, 9)},
               {"lon_deg", RoundToDecimals(r.lon_deg, 9)},
               {"amsl_m", RoundToDecimals(r.amsl_m, 3)},
               {"relative_alt_m", RoundToDecimals(r.relative_alt_m, 3)},
               {"enu_m", Json::array({RoundToDecimals(r.point_enu_m.x(), 3), RoundToDecimals(r.point_enu_m.y(), 3),
                                      RoundToDecimals(r.point_enu_m.z(), 3)})},
               {"axes_within_deg", RoundToDecimals(r.fit_angle_deg, 4)}});
    }
    break;  // every ROI-tracking mission detects the same stretches
  }
  j["points_of_interest"] = rois;
  Json outputs = Json::array();
  for (const auto& r : result.reports) {
    const Mission& fm = result.missions[r.mission];
    Json o;
    o["format"] = FormatName(r.format);
    o["file"] = r.file_name;
    o["waypoints"] = static_cast<int>(fm.waypoints.size());
    o["path_model"] = fm.turn_model == TurnModel::kStraight ? "straight legs" : "coordinated turns";
    o["deviation_reached_m"] = RoundToDecimals(fm.max_deviation_reached_m, 4);
    if (fm.turn_model != TurnModel::kStraight) {
      o["straight_leg_deviation_m"] = RoundToDecimals(fm.straight_deviation_reached_m, 4);
    }
    o["angle_error_reached_deg"] = RoundToDecimals(fm.max_angle_error_reached_deg, 4);
    o["points_of_interest"] = static_cast<int>(fm.rois.size());
    if (IsMavlinkFormat(r.format)) o["mission_items"] = r.mission_items;
    o["notes"] = r.notes;
    Json violations = Json::array();
    for (const auto& v : r.violations) {
      violations.push_back(Json{{"waypoint", v.waypoint}, {"limit", v.limit}, {"message", v.message}});
    }
    o["violations"] = violations;
    outputs.push_back(o);
  }
  j["outputs"] = outputs;
  return j;
}

std::string ReportText(const ExportResult& result, const ExportOptions& options) {
  const Mission& m = result.mission;
  std::string out = fmt::format(
      "{} waypoints from {} plan samples; deviation reached {:.3f} m (limit {:g} m), angle error {:.2f} deg "
      "(limit {:g} deg)\n",
      m.waypoints.size(), m.plan_sample_count, m.max_deviation_reached_m, options.build.selection.max_deviation_m,
      m.max_angle_error_reached_deg, options.build.selection.max_angle_deg);
  if (m.cut_count > 0) {
    out += fmt::format(
        "{} cut(s) between shots: transit legs at {:g} m/s with recording off (the plan jumps there; mission times "
        "after a cut are not the plan's)\n",
        m.cut_count, m.transit_speed_mps);
  }
  for (const Mission& mission : result.missions) {
    if (mission.roi_tracking == RoiTracking::kNone) continue;
    for (size_t k = 0; k < mission.rois.size(); ++k) {
      const MissionRoi& r = mission.rois[k];
      out += fmt::format(
          "point of interest {}: t {:.2f}-{:.2f} s at {:.7f}, {:.7f}, {:.2f} m AMSL ({:.2f} m above home); every "
          "camera "
          "axis within {:.2f} deg of it\n",
          k + 1, r.start_time_s, r.end_time_s, r.lat_deg, r.lon_deg, r.amsl_m, r.relative_alt_m, r.fit_angle_deg);
    }
    break;
  }
  for (const auto& r : result.reports) {
    const Mission& fm = result.missions[r.mission];
    out += fmt::format("{}: {} ({} waypoints, deviation {:.3f} m", FormatName(r.format), r.file_name,
                       fm.waypoints.size(), fm.max_deviation_reached_m);
    if (fm.turn_model != TurnModel::kStraight) {
      out += fmt::format(" with coordinated turns, {:.3f} m as straight legs", fm.straight_deviation_reached_m);
    }
    out += fmt::format(", angle {:.2f} deg", fm.max_angle_error_reached_deg);
    if (!fm.rois.empty()) out += fmt::format(", {} point(s) of interest", fm.rois.size());
    if (IsMavlinkFormat(r.format))
      out += fmt::format("; {} mission items, {}", r.mission_items, FirmwareName(result.firmware));
    out += ")\n";
    for (const auto& n : r.notes) out += "  note: " + n + "\n";
    for (const auto& v : r.violations) out += "  LIMIT (forced): " + v.message + "\n";
  }
  return out;
}

}  // namespace cinepath::exporter
