#include "export/exporter.h"

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
  if (formats.empty()) throw InputError("--format: at least one format is required");
  for (size_t i = 0; i < formats.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (formats[i] == formats[j]) {
        throw InputError(std::string("--format: '") + FormatName(formats[i]) + "' given twice");
      }
    }
    const Format f = formats[i];
    if (IsMavlinkFormat(f) && altitude_ref == AltitudeRef::kEllipsoid) {
      throw InputError(std::string("--altitude-ref ellipsoid: ") + FormatName(f) +
                       " carries altitudes relative to home or AMSL only (MAVLink frames 3 / 0)");
    }
    if ((f == Format::kDjiMsdkJson || f == Format::kLitchiCsv) && altitude_ref != AltitudeRef::kRelative) {
      throw InputError(std::string("--altitude-ref ") + AltitudeRefName(altitude_ref) + ": " + FormatName(f) +
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
  const DroneProfile& profile = FindDroneProfile(
      options.drone_profile.empty() ? std::string(DefaultProfileName(options.firmware)) : options.drone_profile);
  MissionBuildOptions build = options.build;
  build.absolute_altitudes = options.altitude_ref != AltitudeRef::kRelative;

  ExportResult result;
  result.mission = BuildMission(trajectory, build);
  const Mission& mission = result.mission;

  for (Format format : options.formats) {
    FormatReport report;
    report.format = format;
    report.file_name = FormatFileName(format);
    ExportFile file{report.file_name, ""};
    if (IsMavlinkFormat(format)) {
      const MavMission items = BuildMavMission(mission, options.firmware, options.altitude_ref);
      report.notes = items.notes;
      report.mission_items = static_cast<int>(items.items.size());
      if (format == Format::kQgcPlan) file.contents = WriteQgcPlan(mission, items, options.firmware, options.altitude_ref);
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
  j["drone"] = options.drone_profile.empty() ? DefaultProfileName(options.firmware) : options.drone_profile;
  j["altitude_ref"] = AltitudeRefName(options.altitude_ref);
  j["home"] = Json{{"lat_deg", m.home.lat_deg}, {"lon_deg", m.home.lon_deg},
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
  Json outputs = Json::array();
  for (const auto& r : result.reports) {
    Json o;
    o["format"] = FormatName(r.format);
    o["file"] = r.file_name;
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
  for (const auto& r : result.reports) {
    out += fmt::format("{}: {}", FormatName(r.format), r.file_name);
    if (IsMavlinkFormat(r.format)) out += fmt::format(" ({} mission items, {})", r.mission_items, FirmwareName(options.firmware));
    out += "\n";
    for (const auto& n : r.notes) out += "  note: " + n + "\n";
    for (const auto& v : r.violations) out += "  LIMIT (forced): " + v.message + "\n";
  }
  return out;
}

}  // namespace cinepath::exporter
