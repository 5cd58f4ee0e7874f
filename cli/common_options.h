// Options every stage shares : --progress and --depfile.
//   CommonOptions common;  common.Add(app);            // in Setup()
//   Progress p("mesh", n, common.progress_mode());     // in Run()
//   common.WriteDepfileIfAsked({output}, {inputs...});  // after the outputs landed
#pragma once

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/depfile.h"
#include "core/progress.h"
#include "core/quality.h"

namespace cinepath::cli {

// A finite number > 0, with a message a person can read ("must be a finite number > 0, got 0"), where
// CLI::PositiveNumber prints its range up to DBL_MAX.
inline const CLI::Validator& PositiveFinite() {
  static const CLI::Validator v(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || !std::isfinite(x) || !(x > 0)) {
          return "must be a finite number > 0, got " + text;
        }
        return {};
      },
      "POSITIVE");
  return v;
}

// "cinepath <command>: warning: <line>" on stderr for each line (a plan's drone field taken from its
// profile, core/plan_file.h TeamPlanNotes).
inline void PrintWarnings(const std::string& command, const std::vector<std::string>& lines) {
  for (const auto& line : lines) std::cerr << "cinepath " << command << ": warning: " << line << "\n";
}

// "a, b, c": the names of a registry (formats, drones, shot types, AOVs) for a help text, so that --help
// lists what the code declares rather than a hand-kept copy.
template <typename Names>
std::string JoinNames(const Names& names, const char* separator = ", ") {
  std::string out;
  for (const auto& name : names) {
    if (!out.empty()) out += separator;
    out += name;
  }
  return out;
}

// --quality draft|standard|final (core/quality.h), with what this stage's rungs trade, e.g.
// "knot spacing, iterations, tolerance": one list of choices and one help line for every stage.
inline CLI::Option* AddQualityOption(CLI::App& app, std::string* quality, const std::string& what) {
  return app.add_option("--quality", *quality, "Speed for accuracy: " + what + " (default " + *quality + ")")
      ->check(CLI::IsMember(QualityNames()));
}

class CommonOptions {
 public:
  void Add(CLI::App& app) {
    app.add_option("--progress", progress_, "Progress bar: auto (only on a terminal), always, never")
        ->check(CLI::IsMember({"auto", "always", "never"}));
    app.add_option("--depfile", depfile_, "Write a make-style dependency line for what this run read");
  }
  ProgressMode progress_mode() const { return ParseProgressMode(progress_); }
  void WriteDepfileIfAsked(const std::vector<std::string>& targets,
                           const std::vector<std::string>& dependencies) const {
    if (!depfile_.empty()) WriteDepfile(depfile_, targets, dependencies);
  }

 private:
  std::string progress_ = "auto";
  std::string depfile_;
};

}  // namespace cinepath::cli
