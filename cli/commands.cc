// The registry: every subcommand's name, one-line summary and factory, in the order
// `cinepath --help` lists them. A subcommand whose area library is not built is left out
// (CINEPATH_WITH_<AREA>, set by cli/CMakeLists.txt).
#include "cli/command.h"
#include "cli/command_plugin.h"

namespace cinepath::cli {

std::unique_ptr<Command> MakeLensCommand();
#ifdef CINEPATH_WITH_PHOTOGRAMMETRY
// A plugin module (cli/command_plugin.h): photogrammetry's libraries load only for this command.
std::unique_ptr<Command> MakeMeshCommand() { return LoadCommandPlugin("libcinepath_cmd_mesh.so"); }
#endif
#ifdef CINEPATH_WITH_SHOTS
std::unique_ptr<Command> MakePlanCommand();
#endif
#ifdef CINEPATH_WITH_OPTIMIZER
// A plugin module: Ceres, CGAL and Embree load only for this command.
std::unique_ptr<Command> MakeOptimizeCommand() { return LoadCommandPlugin("libcinepath_cmd_optimize.so"); }
#endif
#ifdef CINEPATH_WITH_PREVIEW
// A plugin module: Embree, libjpeg and libpng load only for this command.
std::unique_ptr<Command> MakeRenderCommand() { return LoadCommandPlugin("libcinepath_cmd_render.so"); }
#endif
#ifdef CINEPATH_WITH_VIEWER
// A plugin module: the GLB reader (Draco) loads only for this command.
std::unique_ptr<Command> MakeViewCommand() { return LoadCommandPlugin("libcinepath_cmd_view.so"); }
#endif
#ifdef CINEPATH_WITH_EXPORT
std::unique_ptr<Command> MakeExportCommand();
std::unique_ptr<Command> MakeInfoCommand();
#endif

const std::vector<CommandInfo>& Commands() {
  static const std::vector<CommandInfo> commands = {
#ifdef CINEPATH_WITH_PHOTOGRAMMETRY
      {"mesh", "COLMAP reconstruction -> cleaned, georeferenced mesh (scene.glb + scene.json)", &MakeMeshCommand},
#endif
#ifdef CINEPATH_WITH_SHOTS
      {"plan", "shot list -> keyframed, per-frame camera flight with lens tracks (plan.json)", &MakePlanCommand},
#endif
#ifdef CINEPATH_WITH_OPTIMIZER
      {"optimize", "plan (+ scene) -> plan with the drone path and the lens optimized together (Ceres)",
       &MakeOptimizeCommand},
#endif
#ifdef CINEPATH_WITH_PREVIEW
      {"render", "plan + scene -> ray-traced thin-lens previews of every frame (depth of field, motion blur)",
       &MakeRenderCommand},
#endif
#ifdef CINEPATH_WITH_VIEWER
      {"view", "plan (+ scene, frames) -> one offline HTML previs page: 3D flight, timeline, camera view, lens",
       &MakeViewCommand},
#endif
#ifdef CINEPATH_WITH_EXPORT
      {"export", "plan -> drone missions (QGC .plan/WPL, MAVLink, DJI WPML/MSDK, Litchi CSV)", &MakeExportCommand},
      {"info", "inspect a cinepath file or mission, print a summary or JSON", &MakeInfoCommand},
#endif
      {"lens", "depth-of-field calculator: hyperfocal distance, near/far limits, field of view, blur",
       &MakeLensCommand},
  };
  return commands;
}

}  // namespace cinepath::cli
