// cinepath view: plan.json (+ scene.json, + render's frames) -> one self-contained offline HTML previs
// page (docs/view.md). A plugin module (cli/command_plugin.h): the GLB reader (Draco) loads only when
// this command runs.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/command_plugin.h"
#include "cli/common_options.h"
#include "core/file_io.h"
#include "viewer/previs_page.h"

namespace cinepath::cli {
namespace {

class ViewCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("plan", plan_path_, "plan.json from `cinepath plan` / `cinepath optimize`")->required();
    app.add_option("--scene", scene_path_, "scene.json; its mesh (the GLB beside it) is drawn under the flight");
    app.add_option("--frames", frames_dir_,
                   "Folder of `cinepath render` frames (frame_%06d.png/.jpg): shown in the camera view (several "
                   "drones: render's folder, whose edit/ is taken)");
    app.add_option("-o,--output", output_path_, "The HTML page to write (- for stdout)")->required();
    common_.Add(app);
  }

  int Run() override {
    viewer::ViewOptions options;
    options.plan = plan_path_;
    if (!scene_path_.empty()) options.scene = scene_path_;
    if (!frames_dir_.empty()) options.frames_dir = frames_dir_;
    const viewer::PrevisPage page = viewer::BuildPrevisPage(options);
    PrintWarnings("view", page.notes);
    WriteFileAtomic(output_path_, page.html);
    common_.WriteDepfileIfAsked({output_path_}, page.inputs);
    return 0;
  }

  FieldFlags field_flags() const override { return {{"progress", "--progress"}}; }

 private:
  std::string plan_path_, scene_path_, frames_dir_, output_path_;
  CommonOptions common_;
};

}  // namespace

std::unique_ptr<Command> MakeViewCommand() { return std::make_unique<ViewCommand>(); }

}  // namespace cinepath::cli

CINEPATH_COMMAND_PLUGIN(MakeViewCommand)
