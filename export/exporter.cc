#include "export/exporter.h"

#include <algorithm>

#include <fmt/format.h>

#include "core/error.h"
#include "export/dji_msdk_json.h"
#include "export/dji_wpml.h"
#include "export/litchi_csv.h"
#include "export/mavlink_bin.h"
#include "export/mavlink_mission.h"
#include "export/msdk_spacing.h"
#include "export/qgc_plan.h"
#include "export/qgc_wpl.h"

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

ExportResult ExportMission(const Trajectory& trajectory, const ExportOptions& options) {
  options.Check();
  const DroneProfile& profile = options.build.drone ? *options.build.drone : trajectory.drone;
  MissionBuildOptions build = options.build;
  build.absolute_altitudes = options.altitude_ref != AltitudeRef::kRelative;

  ExportResult result;
  // One Mission per flight model (roi tracking, turn model), in the order formats ask for them.
  std::vector<std::pair<RoiTracking, TurnModel>> models;
  const bool roi = options.roi == RoiMode::kAuto;
  auto model_of = [&](Format format) -> std::pair<RoiTracking, TurnModel> {
    if (IsMavlinkFormat(format) || format == Format::kLitchiCsv) {
      return {roi ? RoiTracking::kCamera : RoiTracking::kNone, TurnModel::kStraight};
    }
    if (format == Format::kDjiWpml) {
      return {roi ? RoiTracking::kHeading : RoiTracking::kNone, TurnModel::kDjiCoordinatedTurn};
    }
    return {RoiTracking::kNone, TurnModel::kStraight};  // MSDK v4: headingMode is mission-wide
  };
  for (Format format : options.formats) {
    const auto model = model_of(format);
    const auto found = std::find(models.begin(), models.end(), model);
    if (found != models.end()) continue;
    models.push_back(model);
    MissionBuildOptions b = build;
    b.selection.roi_tracking = model.first;
    b.turn_model = model.second;
    result.missions.push_back(BuildMission(trajectory, b));
  }

  for (Format format : options.formats) {
    const auto model = model_of(format);
    const int mission_index = static_cast<int>(std::find(models.begin(), models.end(), model) - models.begin());
    const Mission& mission = result.missions[mission_index];
    FormatReport report;
    report.mission = mission_index;
    report.format = format;
    report.file_name = FormatFileName(format);
    ExportFile file{report.file_name, ""};
    if (IsMavlinkFormat(format)) {
      const MavMission items = BuildMavMission(mission, options.firmware, options.altitude_ref);
      report.notes = items.notes;
      report.mission_items = static_cast<int>(items.items.size());
      if (format == Format::kQgcPlan)
        file.contents = WriteQgcPlan(mission, items, options.firmware, options.altitude_ref);
      if (format == Format::kQgcWpl) file.contents = WriteQgcWpl(mission, items);
      if (format == Format::kMavlinkBin) file.contents = WriteMavlinkBin(mission, items, options.firmware);
    } else if (format == Format::kDjiWpml) {
      const WpmlDocuments docs = WriteWpmlDocuments(mission, profile, options.altitude_ref);
      report.notes = docs.notes;
      file.contents = WriteDjiKmz(docs);
    } else if (format == Format::kDjiMsdkJson) {
      std::vector<std::string> merge_notes;
      const Mission merged = MergeCloseWaypoints(mission, LimitsOf(format).min_spacing_m, merge_notes);
      MsdkJson json = WriteDjiMsdkJson(merged);
      report.notes = json.notes;
      report.notes.insert(report.notes.end(), merge_notes.begin(), merge_notes.end());
      for (const Mission& other : result.missions) {
        if (other.rois.empty()) continue;
        report.notes.push_back(
            "points of interest not used: MSDK v4's headingMode TOWARD_POINT_OF_INTEREST is mission-wide; headings and "
            "gimbal pitch are per waypoint");
        break;
      }
      file.contents = std::move(json.text);
      report.violations = ValidateMission(merged, format, profile, 0);
    } else if (format == Format::kLitchiCsv) {
      LitchiCsv csv = WriteLitchiCsv(mission);
      report.notes = csv.notes;
      file.contents = std::move(csv.text);
    }
    if (format != Format::kDjiMsdkJson) {
      report.violations = ValidateMission(mission, format, profile, report.mission_items);
    }
    result.files.push_back(std::move(file));
    result.reports.push_back(std::move(report));
  }
  result.mission = result.missions[result.reports.front().mission];
  result.drone_name = profile.name;

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
  j["firmware"] = FirmwareName(options.firmware);
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
      out += fmt::format("; {} mission items, {}", r.mission_items, FirmwareName(options.firmware));
    out += ")\n";
    for (const auto& n : r.notes) out += "  note: " + n + "\n";
    for (const auto& v : r.violations) out += "  LIMIT (forced): " + v.message + "\n";
  }
  return out;
}

}  // namespace cinepath::exporter
