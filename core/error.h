// Typed errors shared by every cinepath library, and the exit codes the CLI maps them to.
//
// Library code throws; only cli/ turns an error into an exit code (docs/design.md, "Conventions"):
//   InputError       -> 2  usage or bad input (a file, a field, an option); message names where
//   InfeasibleError  -> 3  the result fails validation (infeasible plan, mission over a limit)
//   RuntimeError     -> 1  anything else that went wrong at run time (I/O failure, a tool crashed)
//   InternalError    -> 1  a broken invariant (CINEPATH_CHECK); a bug in cinepath
#pragma once

#include <stdexcept>
#include <string>

namespace cinepath {

enum class ExitCode : int {
  kSuccess = 0,
  kRuntimeFailure = 1,
  kBadInput = 2,
  kValidationFailed = 3,
};

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  virtual ExitCode exit_code() const { return ExitCode::kRuntimeFailure; }
};

// Bad input: the message says which file and which field, line, byte offset or option.
class InputError : public Error {
 public:
  using Error::Error;
  ExitCode exit_code() const override { return ExitCode::kBadInput; }
};

// The request was understood but its result fails validation (exit 3).
class InfeasibleError : public Error {
 public:
  using Error::Error;
  ExitCode exit_code() const override { return ExitCode::kValidationFailed; }
};

class RuntimeError : public Error {
 public:
  using Error::Error;
};

class InternalError : public Error {
 public:
  using Error::Error;
};

// "where: what" — the one way messages are composed, e.g. Located("shots.json: shots[2].radius_m",
// "must be > 0").
inline std::string Located(const std::string& where, const std::string& what) {
  return where.empty() ? what : where + ": " + what;
}

[[noreturn]] void ThrowInternal(const char* file, int line, const char* condition);

}  // namespace cinepath

// Guards an invariant; a failure is a cinepath bug (exit 1, file:line in the message).
// (Not named CHECK: glog, pulled in by Ceres, owns that name.)
#define CINEPATH_CHECK(condition) ((condition) ? (void)0 : ::cinepath::ThrowInternal(__FILE__, __LINE__, #condition))
