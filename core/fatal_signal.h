// What a fatal signal says: a crash inside a library (a division by zero in CGAL, a bad read in a solver)
// ends the process with a message that names the command and the step that was running, and exit code 1
// (a runtime failure), instead of the shell's bare "Floating point exception" and exit code 136.
//
// This is the last line of defence, not the error path: every library call known to trap on degenerate
// input is guarded before it is called (photogrammetry/surface/surface_poisson.h, PoissonInputProblem) and fails
// with a typed error. A signal handler cannot unwind, so nothing after the signal runs: outputs are only
// ever renamed into place once complete (core/file_io.h), so none is left half written; a staged
// temporary file may remain beside its target.
#pragma once

namespace cinepath {

// Installs the report for SIGFPE, SIGSEGV, SIGBUS and SIGILL; `command` (static storage) names the
// subcommand. Not installed in a build with AddressSanitizer, whose own report says more.
void InstallFatalSignalReport(const char* command);

// The step that is running, for the report (a string literal); scopes nest and restore the outer step.
class CurrentStep {
 public:
  explicit CurrentStep(const char* step);
  ~CurrentStep();
  CurrentStep(const CurrentStep&) = delete;
  CurrentStep& operator=(const CurrentStep&) = delete;

 private:
  const char* outer_;
};

// The step that is running now, or null (for tests).
const char* RunningStep();

}  // namespace cinepath
