// cinepath export: plan.json -> drone missions and camera tracks (docs/export.md).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/common_options.h"
#include "core/drone_profiles.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/glb_container.h"
#include "core/ground.h"
#include "core/json.h"
#include "core/number_format.h"
#include "core/plan_file.h"
#include "core/reframe.h"
#include "core/scene_file.h"
#include "export/camera_track.h"
#include "export/exporter.h"
#include "export/flight_export.h"
#include "export/formats.h"

namespace cinepath::cli {
namespace {

using exporter::AltitudeRef;

class ExportCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("plan", plan_path_, "plan.json from `cinepath plan` / `cinepath optimize`")->required();
    app.add_option("--scene", scene_path_,
                   "scene.json: its WGS84 origin when the plan has none, and its mesh's ground under the first "
                   "sample as home (take-off), or to check --home against; for gltf-camera and nuke-chan the "
                   "frame the cameras are written in, and gltf-camera's mesh");
    std::vector<std::string> missions, cameras;
    for (const auto& f : exporter::Formats())
      (f.kind == exporter::FormatKind::kMission ? missions : cameras).push_back(f.name);
    app.add_option("--format", format_names_,
                   "Output format (repeatable): " + JoinNames(missions) + " (missions); " + JoinNames(cameras) +
                       " (camera tracks)")
        ->required();
    app.add_option("--firmware", firmware_name_,
                   "MAVLink target firmware, px4 or ardupilot, for every drone (default: each drone profile's; "
                   "px4 for DJI and custom profiles). A report note says when it overrides a profile's");
    app.add_option("--drone", drone_name_,
                   "Drone profile to check the missions against: " + JoinNames(DroneProfileNames()) +
                       " (docs/drones.md; default: the plan's drone block)");
    app.add_option("--altitude-ref", altitude_ref_name_, "relative (default, to home), amsl (EGM96) or ellipsoid");
    app.add_option("--home", home_text_,
                   "Home / take-off point LAT,LON,ALT (ALT metres AMSL); default: the ground under the first sample "
                   "with --scene's mesh, else the origin");
    app.add_option("--takeoff-tolerance-m", takeoff_tolerance_m_,
                   "With --home and --scene's mesh: warn (exit 3 with --strict) when home's altitude and the mesh's "
                   "ground there differ by more (3)")
        ->check(PositiveFinite());
    app.add_flag("--strict", strict_, "Exit 3 (writing nothing) when --home disagrees with the mesh's ground");
    app.add_option("--max-deviation-m", max_deviation_m_, "Largest distance of the flown legs from the plan (0.5)");
    app.add_option("--max-angle-deg", max_angle_deg_, "Largest heading / gimbal error along a leg (3)");
    app.add_option("--roi", roi_name_, "Points of interest: auto (default: detect and let the target aim) or off");
    app.add_flag("--force", force_, "Write the mission even when it breaks a platform limit (still reported)");
    app.add_flag("--json", json_, "Print the report as JSON instead of text");
    app.add_option("-o,--output", output_dir_, "Output folder")->required();
    common_.Add(app);
  }

  int Run() override {
    exporter::ExportOptions options;
    for (const auto& name : format_names_) options.formats.push_back(exporter::ParseFormat(name));
    if (!firmware_name_.empty()) options.firmware = exporter::ParseFirmware(firmware_name_);
    if (!drone_name_.empty()) options.build.drone = RequireDroneProfile(drone_name_, "--drone");
    if (altitude_ref_name_ == "relative") {
      options.altitude_ref = AltitudeRef::kRelative;
    } else if (altitude_ref_name_ == "amsl") {
      options.altitude_ref = AltitudeRef::kAmsl;
    } else if (altitude_ref_name_ == "ellipsoid") {
      options.altitude_ref = AltitudeRef::kEllipsoid;
    } else {
      throw InputError("--altitude-ref: unknown reference '" + altitude_ref_name_ +
                       "' (known: relative, amsl, ellipsoid)");
    }
    if (roi_name_ == "auto") {
      options.roi = exporter::RoiMode::kAuto;
    } else if (roi_name_ == "off") {
      options.roi = exporter::RoiMode::kOff;
    } else {
      throw InputError("--roi: unknown mode '" + roi_name_ + "' (known: auto, off)");
    }
    options.force = force_;
    options.build.plan_name = plan_path_;
    options.build.selection.max_deviation_m = max_deviation_m_;
    options.build.selection.max_angle_deg = max_angle_deg_;
    if (!home_text_.empty()) options.build.home = exporter::ParseHomeSpec(home_text_, "--home");
    options.Check();  // option errors before any file is read
    std::vector<exporter::Format> camera_formats;
    std::erase_if(options.formats, [&](exporter::Format f) {
      if (!exporter::IsCameraTrackFormat(f)) return false;
      camera_formats.push_back(f);
      return true;
    });

    TeamPlan team = ReadTeamPlanFile(plan_path_);
    PrintWarnings("export", TeamPlanNotes(team));
    const CameraTracks cameras = WriteCameraTracks(team, camera_formats);
    if (options.formats.empty()) return RunCamerasOnly(cameras);
    return RunMissions(team, options, cameras);
  }

  // The camera-track formats' files (into OUTPUT itself, for one drone or several), their report, and
  // the files they read.
  struct CameraTracks {
    std::vector<exporter::CameraFile> files;
    Json report = Json::array();
    std::string text;
    std::vector<std::string> inputs;
  };

  // Every drone's track, in --scene's frame when it has an origin (core/reframe.h: exact, through ECEF,
  // so a plan about another origin, across the antimeridian or kilometres away, lands on the mesh), with
  // --scene's mesh in the GLB.
  CameraTracks WriteCameraTracks(const TeamPlan& plan, const std::vector<exporter::Format>& formats) const {
    CameraTracks out;
    if (formats.empty()) return out;
    const TeamPlan* team = &plan;
    TeamPlan reframed;
    std::string glb;
    std::string glb_source;
    if (!scene_path_.empty()) {
      const SceneFile scene = ReadSceneFile(scene_path_);
      out.inputs.push_back(scene_path_);
      if (scene.origin && plan.origin) {
        reframed = ReframeToOrigin(plan, *scene.origin);
        team = &reframed;
      }
      const bool gltf = std::find(formats.begin(), formats.end(), exporter::Format::kGltfCamera) != formats.end();
      if (scene.mesh && gltf) {
        glb_source = scene.RequireMesh().string();
        glb = ReadFileToString(scene.RequireMesh());
        out.inputs.push_back(glb_source);
      }
    }
    std::vector<exporter::CameraTrack> tracks;
    for (const auto& flight : team->flights) {
      CheckDroneFolderName(flight.name, plan_path_);
      tracks.push_back(exporter::TrackOfFlight(flight.plan, flight.name, plan_path_, !team->single));
    }
    const exporter::CameraTrack& first = tracks.front();
    for (exporter::Format format : formats) {
      const exporter::FormatInfo& info = exporter::InfoOf(format);
      const std::vector<exporter::CameraFile> files = info.write_cameras({tracks, glb, glb_source});
      Json names = Json::array();
      std::string list;
      for (const auto& file : files) {
        names.push_back(file.file_name);
        list += (list.empty() ? "" : ", ") + file.file_name;
        out.files.push_back(file);
      }
      const auto [frame_start, frame_end] = exporter::FrameRange(tracks);
      const bool mesh = format == exporter::Format::kGltfCamera && !glb.empty();
      const std::string mesh_name = std::filesystem::path(glb_source).filename().string();
      Json notes = Json::array();
      if (mesh && SplitGlb(glb, glb_source).json.find("KHR_draco_mesh_compression") != std::string_view::npos) {
        notes.push_back(mesh_name +
                        " is Draco-compressed: Debian's Blender 3.4 has no Draco decoder and cannot import it (a "
                        "scene built without --draco can)");
      }
      out.report.push_back(Json{{"format", info.name},
                                {"files", names},
                                {"cameras", tracks.size()},
                                {"frame_rate_hz", first.frame_rate_hz},
                                {"frame_start", frame_start},
                                {"frame_end", frame_end},
                                {"scene_mesh", mesh ? Json(mesh_name) : Json(nullptr)},
                                {"notes", notes}});
      out.text += std::string(info.name) + ": " + list + " (" + std::to_string(tracks.size()) +
                  (tracks.size() == 1 ? " camera" : " cameras") + ", frames " + std::to_string(frame_start) + "-" +
                  std::to_string(frame_end) + " at " + FormatShortest(first.frame_rate_hz) + " fps" +
                  (mesh ? ", with the mesh of " + mesh_name : std::string()) + ")\n";
      for (const auto& note : notes) out.text += "  note: " + note.get<std::string>() + "\n";
    }
    return out;
  }

  void AddCameraFiles(const CameraTracks& cameras, AtomicOutputs& outputs, std::vector<std::string>& targets,
                      std::vector<std::string>& inputs) const {
    for (const auto& file : cameras.files) {
      outputs.Add(std::filesystem::path(output_dir_) / file.file_name, file.contents);
      targets.push_back((std::filesystem::path(output_dir_) / file.file_name).string());
    }
    for (const auto& input : cameras.inputs) {
      if (std::find(inputs.begin(), inputs.end(), input) == inputs.end()) inputs.push_back(input);
    }
  }

  // Only camera tracks: no mission, no home, no origin needed.
  int RunCamerasOnly(const CameraTracks& cameras) const {
    std::vector<std::string> inputs = {plan_path_};
    std::vector<std::string> targets;
    const Json report = Json{{"camera_tracks", cameras.report}};
    EnsureDirectory(output_dir_);
    AtomicOutputs outputs;
    AddCameraFiles(cameras, outputs, targets, inputs);
    outputs.Add(std::filesystem::path(output_dir_) / "export_report.json", DumpJson(report));
    targets.push_back((std::filesystem::path(output_dir_) / "export_report.json").string());
    outputs.Commit();
    std::cout << (json_ ? DumpJson(report) : cameras.text);
    common_.WriteDepfileIfAsked(targets, inputs);
    return 0;
  }

  // One mission per flight (export/flight_export.h): a "cinepath.plan/1" plan's files and report go into
  // OUTPUT, a plan of several drones' into OUTPUT/<drone>/ (the file names of a one-drone export) with a
  // report of the drones in OUTPUT.
  int RunMissions(const TeamPlan& team, const exporter::ExportOptions& shared, const CameraTracks& cameras) const {
    exporter::FlightExportOptions options;
    options.shared = shared;
    options.plan_name = plan_path_;
    options.takeoff_tolerance_m = takeoff_tolerance_m_;
    options.strict = strict_;
    options.warn = [](const std::string& message) { std::cerr << "cinepath export: warning: " << message << "\n"; };
    std::vector<std::string> inputs = {plan_path_};
    std::unique_ptr<Ground> ground;
    if (!scene_path_.empty()) {
      const SceneFile scene = ReadSceneFile(scene_path_);
      options.scene_origin = scene.RequireOrigin();
      inputs.push_back(scene_path_);
      if (scene.mesh) {
        inputs.push_back(scene.RequireMesh().string());
        ground = LoadGround(scene.RequireMesh());
        options.ground = ground.get();
      }
    }
    const std::vector<exporter::FlightExport> exports = exporter::ExportFlights(team, options);

    EnsureDirectory(output_dir_);
    AtomicOutputs outputs;
    std::vector<std::string> targets;
    Json report = Json::object();
    Json drones = Json::array();
    std::string text;
    for (const auto& e : exports) {
      const std::filesystem::path dir =
          team.single ? std::filesystem::path(output_dir_) : std::filesystem::path(output_dir_) / e.name;
      const Json flight_report = exporter::ReportJson(e.result, e.options);
      if (!team.single) EnsureDirectory(dir.string());
      for (const auto& file : e.result.files) {
        outputs.Add(dir / file.file_name, file.contents);
        targets.push_back((dir / file.file_name).string());
      }
      if (team.single) {
        report = flight_report;
        text += exporter::ReportText(e.result, e.options);
        continue;
      }
      outputs.Add(dir / "export_report.json", DumpJson(flight_report));
      targets.push_back((dir / "export_report.json").string());
      Json entry = Json{{"name", e.name}, {"folder", e.name}};
      entry.update(flight_report);
      drones.push_back(entry);
      text += "drone " + e.name + " -> " + dir.string() + "/ (profile " + e.result.drone_name + ", home " +
              FormatFixed(e.result.mission.home.lat_deg, 7) + ", " + FormatFixed(e.result.mission.home.lon_deg, 7) +
              ", " + FormatFixed(e.result.mission.home.amsl_m, 2) + " m AMSL)\n";
      for (const auto& line : SplitLines(exporter::ReportText(e.result, e.options))) text += "  " + line + "\n";
    }
    if (!team.single) report = Json{{"drones", drones}};
    if (!cameras.files.empty()) report["camera_tracks"] = cameras.report;
    AddCameraFiles(cameras, outputs, targets, inputs);
    text += cameras.text;
    outputs.Add(std::filesystem::path(output_dir_) / "export_report.json", DumpJson(report));
    targets.push_back((std::filesystem::path(output_dir_) / "export_report.json").string());
    outputs.Commit();
    std::cout << (json_ ? DumpJson(report) : text);
    common_.WriteDepfileIfAsked(targets, inputs);
    return 0;
  }

  static std::vector<std::string> SplitLines(const std::string& text) {
    std::vector<std::string> lines;
    size_t start = 0;
    while (start < text.size()) {
      size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      lines.push_back(text.substr(start, end - start));
      start = end + 1;
    }
    return lines;
  }

  FieldFlags field_flags() const override {
    return {{"formats", "--format"},
            {"firmware", "--firmware"},
            {"altitude_ref", "--altitude-ref"},
            {"max_deviation_m", "--max-deviation-m"},
            {"max_angle_deg", "--max-angle-deg"},
            {"scene_origin", "--scene"},
            {"home", "--home"},
            {"progress", "--progress"}};
  }

 private:
  std::string plan_path_;
  std::string scene_path_;
  std::vector<std::string> format_names_;
  std::string firmware_name_;  // empty: each drone profile's
  std::string drone_name_;
  std::string altitude_ref_name_ = "relative";
  std::string home_text_;
  double max_deviation_m_ = 0.5;
  double takeoff_tolerance_m_ = 3.0;
  bool strict_ = false;
  CommonOptions common_;
  double max_angle_deg_ = 3.0;
  std::string roi_name_ = "auto";
  bool force_ = false;
  bool json_ = false;
  std::string output_dir_;
};

}  // namespace

std::unique_ptr<Command> MakeExportCommand() { return std::make_unique<ExportCommand>(); }

}  // namespace cinepath::cli
