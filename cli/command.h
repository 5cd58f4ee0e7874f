// The subcommand interface. One cli/cmd_<name>.cc per subcommand; each is a thin shell: bind flags
// onto the library's options struct in Setup() (no I/O there), then call the library in Run().
// Errors are thrown as cinepath::Error subclasses and mapped to exit codes by main().
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cli/field_flags.h"

namespace CLI {
class App;
}

namespace cinepath::cli {

class Command {
 public:
  virtual ~Command() = default;
  // Declares options on `app`. Must not open files.
  virtual void Setup(CLI::App& app) = 0;
  // Does the work; returns the exit code (normally 0). Throws cinepath::Error on failure.
  virtual int Run() = 0;
  // Which flag binds which library field (cli/field_flags.h): messages of InputErrors show the flags.
  virtual FieldFlags field_flags() const { return {}; }
};

struct CommandInfo {
  std::string name;
  std::string summary;  // one line, shown by `cinepath --help`
  std::unique_ptr<Command> (*make)();
};

// Every subcommand, in the order `cinepath --help` lists them (cli/commands.cc).
const std::vector<CommandInfo>& Commands();

}  // namespace cinepath::cli
