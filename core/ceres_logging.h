// Ceres reports through glog on stderr: a residual block that evaluated to NaN (with a table of its
// values), a minimizer that stopped. Those lines are for whoever debugs a solver, never for a user's
// terminal: a failure reaches the user as cinepath's own message (core/error.h). QuietCeresLogging() turns
// glog's output below FATAL off, once per process, unless CINEPATH_CERES_TRACE is set (then optimize also
// prints Ceres' progress table, optimizer/optimizer.cc).
// Header-only, for the areas that link Ceres (optimizer, photogrammetry); core itself does not.
#pragma once

#include <cstdlib>

#include <glog/logging.h>

namespace cinepath {

inline void QuietCeresLogging() {
  static const bool quiet = [] {
    const bool trace = std::getenv("CINEPATH_CERES_TRACE") != nullptr;
    if (!trace) FLAGS_minloglevel = google::GLOG_FATAL;
    return !trace;
  }();
  (void)quiet;
}

}  // namespace cinepath
