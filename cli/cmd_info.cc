// cinepath info: inspect a cinepath file or a mission and print a summary or JSON (docs/export.md,
// "cinepath info"). Understands plan.json (one drone or several), QGC .plan and "QGC WPL 110" missions;
// other kinds of files are
// added by the stages that write them.
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/common_options.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/json.h"
#include "core/plan_file.h"
#include "core/team_summary.h"
#include "export/mission_reader.h"

namespace cinepath::cli {
namespace {

class InfoCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("file", path_, "File to inspect (.plan, .waypoints, a plan.json)")->required();
    app.add_flag("--json", json_, "Print JSON instead of text");
  }

  int Run() override {
    const std::string text = ReadFileToString(path_);
    if (IsPlan(text)) {
      const TeamPlan plan = ReadTeamPlanFile(path_);
      PrintWarnings("info", TeamPlanNotes(plan));
      std::cout << (json_ ? DumpJson(TeamPlanSummaryJson(plan)) : TeamPlanSummaryText(plan));
      return 0;
    }
    if (!exporter::LooksLikeMission(text)) {
      throw InputError(path_ + ": not a file kind `cinepath info` understands (plan.json, QGC .plan, QGC WPL 110)");
    }
    const exporter::ReadMission mission =
        text.rfind("QGC WPL", 0) == 0 ? exporter::ParseQgcWpl(text, path_) : exporter::ParseQgcPlan(text, path_);
    std::cout << (json_ ? DumpJson(exporter::MissionSummaryJson(mission)) : exporter::MissionSummaryText(mission));
    return 0;
  }

 private:
  // A plan of one drone ("cinepath.plan/1", read as a team of one) or of several ("cinepath.plan/2").
  static bool IsPlan(const std::string& text) {
    if (text.find("cinepath.plan/") == std::string::npos) return false;
    const Json doc = Json::parse(text, nullptr, false);
    return doc.is_object() && doc.contains("schema") &&
           (doc["schema"] == kPlanSchema || doc["schema"] == kTeamPlanSchema);
  }

  std::string path_;
  bool json_ = false;
};

}  // namespace

std::unique_ptr<Command> MakeInfoCommand() { return std::make_unique<InfoCommand>(); }

}  // namespace cinepath::cli
