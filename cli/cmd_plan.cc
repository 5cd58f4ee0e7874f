// cinepath plan: shot list -> keyframes, one sample per frame, lens tracks and a feasibility
// report (docs/plan.md, plan.json format: docs/plan-format.md).
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/common_options.h"
#include "core/drone_profiles.h"
#include "core/error.h"
#include "core/feasibility.h"
#include "core/file_io.h"
#include "core/ground.h"
#include "core/json.h"
#include "core/number_format.h"
#include "core/plan_file.h"
#include "core/reframe.h"
#include "core/scene_file.h"
#include "shots/plan_plot.h"
#include "shots/plan_warnings.h"
#include "shots/planner.h"
#include "shots/shot_list.h"
#include "shots/shot_type.h"
#include "shots/team_planner.h"

namespace cinepath::cli {
namespace {

class PlanCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("shots", shots_path_,
                   "Shot list (shots.json, docs/plan.md); shot types " + JoinNames(shots::ShotTypeNames()) +
                       "; drones " + JoinNames(DroneProfileNames()))
        ->required();
    app.add_option("--scene", scene_path_,
                   "scene.json: its origin places a shot list without one on WGS84 (a list with its own is planned "
                   "about it, the mesh moved into its frame), and its mesh is the ground (heights above ground, "
                   "actors on the ground, terrain clearance)");
    app.add_option("-o,--output", output_, "Where to write plan.json ('-' = stdout)")->required();
    app.add_option("--csv", csv_path_, "Also write the samples as CSV");
    app.add_option("--plot", plot_path_, "Also write an SVG: top-down and side views, frustums, lens curves");
    app.add_flag("--strict", strict_, "Exit 3 (writing nothing) when any drone or lens limit is broken");
    common_.Add(app);
  }

  int Run() override {
    // Messages name the shot list by its base name, so they read the same wherever it lives.
    const std::string shots_name = std::filesystem::path(shots_path_).filename().string();
    const Json shots_json = ParseJsonText(ReadFileToString(shots_path_), shots_name);
    std::optional<Geodetic> plan_origin;
    std::shared_ptr<const Ground> ground;
    std::vector<std::string> inputs = {shots_path_};
    if (!scene_path_.empty()) {
      const SceneFile scene = ReadSceneFile(scene_path_);
      plan_origin = scene.origin;
      // A shot list made about another origin (a surveyed point, or the scene of an earlier
      // reconstruction) is planned about its own: the mesh is moved into its frame exactly, and the
      // later stages move the plan onto the scene's origin (core/reframe.h).
      std::optional<Eigen::Isometry3d> frame_from_scene;
      const std::optional<Geodetic> own = shots::ShotListOrigin(shots_json, shots_name);
      if (own && scene.origin && !shots::SameOrigin(*own, *scene.origin)) {
        plan_origin = own;
        frame_from_scene = EnuFromEnu(*own, *scene.origin);
      }
      inputs.push_back(scene_path_);
      if (scene.mesh) {
        ground = LoadGround(scene.RequireMesh(), frame_from_scene);
        inputs.push_back(scene.mesh->string());
      }
    }
    const shots::ShotList list = shots::ParseShotList(shots_json, shots_name, plan_origin, ground);
    const TeamPlan plan = shots::PlanTeam(list);
    for (const std::string& w : shots::FloatingActorWarnings(list))
      std::cerr << "cinepath plan: warning: " << w << "\n";
    for (const std::string& w : shots::StopsDeadWarnings(list, plan))
      std::cerr << "cinepath plan: warning: " << w << "\n";
    if (strict_) RefuseBrokenLimits(plan);

    AtomicOutputs outputs;
    outputs.Add(output_, TeamPlanToText(plan));
    if (!csv_path_.empty()) outputs.Add(csv_path_, TeamPlanSamplesToCsv(plan));
    if (!plot_path_.empty()) outputs.Add(plot_path_, shots::PlanToSvg(plan));
    outputs.Commit();

    std::vector<std::string> targets = {output_};
    if (!csv_path_.empty()) targets.push_back(csv_path_);
    if (!plot_path_.empty()) targets.push_back(plot_path_);
    common_.WriteDepfileIfAsked(targets, inputs);
    return 0;
  }

  // --strict: exit 3 naming every broken range, of every flight and of the team.
  static void RefuseBrokenLimits(const TeamPlan& plan) {
    size_t broken = plan.team.conflicts.size();
    for (const auto& f : plan.flights) broken += f.plan.feasibility.violations.size();
    if (broken == 0) return;
    std::string msg = "the plan breaks " + std::to_string(broken) + " limit range(s) (--strict; nothing written):";
    auto range = [](double a, double b) { return FormatFixed(a, 3) + "-" + FormatFixed(b, 3) + " s  "; };
    // Four significant digits, more when they would print the value as the limit (45.0002 > 45, not 45 > 45).
    auto against = [](double value, double limit) {
      int digits = 4;
      while (digits < 9 && FormatSignificant(value, digits) == FormatSignificant(limit, digits)) ++digits;
      return FormatSignificant(value, digits);
    };
    for (const auto& f : plan.flights) {
      for (const auto& v : f.plan.feasibility.violations) {
        const bool minimum = IsMinimumLimit(v.limit);
        const std::string unit = v.unit.empty() ? "" : " " + v.unit;
        msg += "\n  " + range(v.start_time_s, v.end_time_s) + (plan.single ? "" : "drone \"" + f.name + "\"  ") +
               "shot \"" + v.shot + "\"  " + v.limit + ": " + against(v.worst_value, v.limit_value) + unit +
               (minimum ? " < " : " > ") + FormatSignificant(v.limit_value, 4) + unit;
      }
    }
    for (const auto& c : plan.team.conflicts) {
      const bool separation = c.limit == "separation";
      msg +=
          "\n  " + range(c.start_time_s, c.end_time_s) + c.limit + ": drone \"" + c.other + "\" " +
          (separation ? FormatSignificant(c.worst_value, 4) + " m from \"" + c.drone + "\" (< " +
                            FormatSignificant(c.limit_value, 4) + " m)"
                      : "in the shot of \"" + c.drone + "\" (" + FormatSignificant(c.worst_value, 4) + " px across)");
    }
    throw InfeasibleError(msg);
  }

  FieldFlags field_flags() const override {
    return {{"scene_origin", "--scene"}, {"scene_mesh", "--scene"}, {"progress", "--progress"}};
  }

 private:
  std::string shots_path_;
  std::string scene_path_;
  std::string output_;
  std::string csv_path_;
  std::string plot_path_;
  bool strict_ = false;
  CommonOptions common_;
};

}  // namespace

std::unique_ptr<Command> MakePlanCommand() { return std::make_unique<PlanCommand>(); }

}  // namespace cinepath::cli
