// cinepath export: plan.json -> drone missions (docs/export.md).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/common_options.h"
#include "core/drone_profiles.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/ground.h"
#include "core/json.h"
#include "core/number_format.h"
#include "core/plan_file.h"
#include "core/scene_file.h"
#include "export/exporter.h"
#include "export/formats.h"
#include "export/takeoff.h"

namespace cinepath::cli {
namespace {

using exporter::AltitudeRef;

class ExportCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("plan", plan_path_, "plan.json from `cinepath plan` / `cinepath optimize`")->required();
    app.add_option("--scene", scene_path_,
                   "scene.json: its WGS84 origin when the plan has none, and its mesh's ground under the first "
                   "sample as home (take-off), or to check --home against");
    app.add_option("--format", format_names_,
                   "Output format (repeatable): qgc-plan, qgc-wpl, mavlink-bin, dji-wpml, dji-msdk-json, "
                   "litchi-csv")
        ->required();
    app.add_option("--firmware", firmware_name_, "MAVLink target firmware: px4 (default) or ardupilot");
    app.add_option("--drone", drone_name_,
                   "Drone profile to check the missions against: px4-multirotor, ardupilot-copter, dji-m30, "
                   "dji-mini4pro (docs/drones.md; default: the plan's drone block)");
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
    options.firmware = exporter::ParseFirmware(firmware_name_);
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

    const Trajectory plan = ReadPlanFile(plan_path_);
    std::vector<std::string> inputs = {plan_path_};
    if (!scene_path_.empty()) {
      const SceneFile scene = ReadSceneFile(scene_path_);
      options.build.scene_origin = scene.RequireOrigin();
      inputs.push_back(scene_path_);
      if (scene.mesh) {
        inputs.push_back(scene.RequireMesh().string());
        UseTheGroundForHome(plan, scene, &options);
      }
    }
    const exporter::ExportResult result = exporter::ExportMission(plan, options);

    const Json report = exporter::ReportJson(result, options);
    EnsureDirectory(output_dir_);
    AtomicOutputs outputs;
    for (const auto& file : result.files)
      outputs.Add(std::filesystem::path(output_dir_) / file.file_name, file.contents);
    outputs.Add(std::filesystem::path(output_dir_) / "export_report.json", DumpJson(report));
    outputs.Commit();
    std::cout << (json_ ? DumpJson(report) : exporter::ReportText(result, options));
    std::vector<std::string> targets;
    for (const auto& file : result.files)
      targets.push_back((std::filesystem::path(output_dir_) / file.file_name).string());
    targets.push_back((std::filesystem::path(output_dir_) / "export_report.json").string());
    common_.WriteDepfileIfAsked(targets, inputs);
    return 0;
  }

  // Home on the mesh's ground under the first sample, or --home checked against that ground.
  void UseTheGroundForHome(const Trajectory& plan, const SceneFile& scene, exporter::ExportOptions* options) const {
    const std::unique_ptr<Ground> ground = LoadGround(scene.RequireMesh());
    if (!options->build.home) {
      options->build.home = exporter::TakeoffOnGround(plan, scene.RequireOrigin(), *ground);
      return;
    }
    const auto check = exporter::CheckHomeAgainstGround(*options->build.home, scene.RequireOrigin(), *ground);
    if (!check || std::abs(check->difference_m) <= takeoff_tolerance_m_) return;
    const std::string message = "--home: altitude " + FormatFixed(options->build.home->amsl_m, 2) + " m AMSL lies " +
                                FormatFixed(check->difference_m, 2) + " m from the mesh's ground (" +
                                FormatFixed(check->ground_amsl_m, 2) + " m AMSL) there, beyond --takeoff-tolerance-m " +
                                FormatSignificant(takeoff_tolerance_m_, 3) + " m: every relative altitude shifts by it";
    if (strict_) throw InfeasibleError(message + " (--strict; nothing written)");
    std::cerr << "cinepath export: warning: " << message << "\n";
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
  std::string firmware_name_ = "px4";
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
