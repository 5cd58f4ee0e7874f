// cinepath: one executable, one subcommand per stage (see `cinepath --help`).
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/doc_pages.h"
#include "core/error.h"
#include "core/fatal_signal.h"
#include "core/version.h"

namespace {

using cinepath::cli::Commands;

void PrintUsage(std::ostream& os) {
  os << "cinepath " << cinepath::kVersion << " — aerial-cinematography previsualization\n\n"
     << "Usage: cinepath <command> [options]\n"
     << "       cinepath <command> --help\n"
     << "       cinepath help <command>     the options and the examples of its page in docs/\n"
     << "       cinepath --version\n\n"
     << "Commands:\n";
  size_t width = 0;
  for (const auto& c : Commands()) width = std::max(width, c.name.size());
  for (const auto& c : Commands()) {
    os << "  " << c.name << std::string(width + 2 - c.name.size(), ' ') << c.summary << "\n";
  }
  os << "\nExit codes: 0 success, 1 runtime failure, 2 usage or bad input, 3 result fails validation.\n";
}

// `cinepath help <command>`: the command's --help, then the examples of its page in docs/.
int PrintCommandHelp(const std::string& name) {
  for (const auto& info : Commands()) {
    if (info.name != name) continue;
    try {
      auto command = info.make();
      CLI::App app(info.summary, "cinepath " + info.name);
      app.set_help_flag("-h,--help", "Print this help and exit");
      app.get_formatter()->column_width(34);
      command->Setup(app);
      std::cout << app.help();
    } catch (const cinepath::Error& e) {
      std::cerr << "cinepath help: " << e.what() << "\n";
      return static_cast<int>(e.exit_code());
    }
    if (const auto examples = cinepath::cli::DocExamples(name)) {
      std::cout << "\nFrom docs/" << name << ".md:\n\n" << *examples;
    }
    return 0;
  }
  std::cerr << "cinepath help: unknown command '" << name << "'\n\n";
  PrintUsage(std::cerr);
  return static_cast<int>(cinepath::ExitCode::kBadInput);
}

int RunCommand(const cinepath::cli::CommandInfo& info, int argc, char** argv) {
  auto command = info.make();
  CLI::App app(info.summary, "cinepath " + info.name);
  app.set_help_flag("-h,--help", "Print this help and exit");
  app.get_formatter()->column_width(34);
  command->Setup(app);
  try {
    // argv[0] is "cinepath"; CLI11 sees the subcommand's own arguments.
    std::vector<std::string> args;
    for (int i = argc - 1; i >= 2; --i) args.emplace_back(argv[i]);
    app.parse(args);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << "cinepath " << info.name << ": " << e.what() << "\n"
              << "Run 'cinepath " << info.name << " --help' for usage.\n";
    return static_cast<int>(cinepath::ExitCode::kBadInput);
  }
  try {
    return command->Run();
  } catch (const cinepath::InputError& e) {
    throw cinepath::InputError(cinepath::cli::WithFlagNames(e.what(), command->field_flags()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  if (argc < 2) {
    PrintUsage(std::cerr);
    return static_cast<int>(cinepath::ExitCode::kBadInput);
  }
  const std::string first = argv[1];
  if (first == "help" && argc >= 3) return PrintCommandHelp(argv[2]);
  if (first == "--help" || first == "-h" || first == "help") {
    PrintUsage(std::cout);
    return 0;
  }
  if (first == "--version" || first == "version") {
    std::cout << "cinepath " << cinepath::kVersion << "\n";
    return 0;
  }
  for (const auto& info : Commands()) {
    if (info.name != first) continue;
    cinepath::InstallFatalSignalReport(info.name.c_str());
    try {
      return RunCommand(info, argc, argv);
    } catch (const cinepath::Error& e) {
      std::cerr << "cinepath " << info.name << ": " << e.what() << "\n";
      return static_cast<int>(e.exit_code());
    } catch (const std::bad_alloc&) {
      std::cerr << "cinepath " << info.name << ": out of memory\n";
      return static_cast<int>(cinepath::ExitCode::kRuntimeFailure);
    } catch (const std::exception& e) {
      std::cerr << "cinepath " << info.name << ": " << e.what() << "\n";
      return static_cast<int>(cinepath::ExitCode::kRuntimeFailure);
    }
  }
  std::cerr << "cinepath: unknown command '" << first << "'\n\n";
  PrintUsage(std::cerr);
  return static_cast<int>(cinepath::ExitCode::kBadInput);
}
