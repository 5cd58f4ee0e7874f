// cinepath optimize: plan.json (+ scene.json) -> plan.json with the drone path and the lens optimized
// together (docs/optimize.md). A plugin module (cli/command_plugin.h): Ceres, CGAL and Embree load only
// when this command runs.
#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/command_plugin.h"
#include "cli/common_options.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/heap_pages.h"
#include "core/plan_file.h"
#include "core/reframe.h"
#include "core/scene_file.h"
#include "optimizer/team_optimizer.h"
#include "scene/glb_reader.h"

namespace cinepath::cli {
namespace {

using namespace cinepath::optimizer;

class OptimizeCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("plan", plan_path_, "plan.json (docs/plan-format.md)")->required();
    app.add_option("--scene", scene_path_, "scene.json: clearance from its mesh and lines of sight through it");
    AddQualityOption(app, &quality_, "knot spacing, iterations, tolerance, multiplier rounds");
    app.add_option("--report", report_path_, "Also write report.json: every cost and limit before and after");
    app.add_flag("--strict", strict_,
                 "Exit 3 (writing nothing) when a limit is still broken or the subject still hidden after optimizing");
    app.add_option("-o,--output", output_, "The optimized plan.json, or - for stdout")->required();
    common_.Add(app);
  }

  int Run() override {
    // Each stage of the ladder builds its problem (tens of thousands of small cost objects) and frees it:
    // the next reuses those pages, and the main thread's come in 2 MiB pages (core/heap_pages.h).
    PrepareHeapForLargeBuffers(kCommandHeapReserveBytes);
    TeamOptimizeInput input;
    input.plan = ReadTeamPlanFile(plan_path_);
    input.plan_source = plan_path_;
    PrintWarnings("optimize", TeamPlanNotes(input.plan));
    std::vector<std::string> inputs = {plan_path_};
    scene::SceneMesh mesh;
    if (!scene_path_.empty()) {
      const SceneFile scene = ReadSceneFile(scene_path_);
      const auto& glb = scene.RequireMesh();
      mesh = scene::ReadGlbFile(glb);
      if (scene.origin && input.plan.origin) input.plan = ReframeToOrigin(input.plan, *scene.origin);
      input.mesh = &mesh;
      input.scene_source = std::filesystem::path(scene_path_).filename().string();  // no folders: the bytes
      // stay the same wherever the files are
      inputs.push_back(scene_path_);
      inputs.push_back(glb.string());
    }
    const TeamOptimizeResult result = OptimizeTeam(input, OptimizeOptions::ForQuality(ParseQuality(quality_)));
    if (strict_ && !result.failure.empty()) {
      throw InfeasibleError("after optimizing, " + result.failure + " (--strict; nothing written)");
    }
    AtomicOutputs outputs;
    outputs.Add(output_, TeamPlanToText(result.plan));
    std::vector<std::string> targets = {output_};
    if (!report_path_.empty()) {
      outputs.Add(report_path_, DumpJson(result.report));
      targets.push_back(report_path_);
    }
    outputs.Commit();
    common_.WriteDepfileIfAsked(targets, inputs);
    return 0;
  }

  FieldFlags field_flags() const override { return {{"progress", "--progress"}}; }

 private:
  std::string plan_path_, scene_path_, report_path_, output_, quality_ = "standard";
  bool strict_ = false;
  CommonOptions common_;
};

}  // namespace

std::unique_ptr<Command> MakeOptimizeCommand() { return std::make_unique<OptimizeCommand>(); }

}  // namespace cinepath::cli

CINEPATH_COMMAND_PLUGIN(MakeOptimizeCommand)
