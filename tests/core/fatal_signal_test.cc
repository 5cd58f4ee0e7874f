#include "core/fatal_signal.h"

#include <csignal>

#include <gtest/gtest.h>

namespace cinepath {
namespace {

TEST(CurrentStep, NestsAndRestoresTheOuterStep) {
  EXPECT_EQ(RunningStep(), nullptr);
  {
    const CurrentStep outer("surface");
    EXPECT_STREQ(RunningStep(), "surface");
    {
      const CurrentStep inner("poisson");
      EXPECT_STREQ(RunningStep(), "poisson");
    }
    EXPECT_STREQ(RunningStep(), "surface");
  }
  EXPECT_EQ(RunningStep(), nullptr);
}

#if !defined(__SANITIZE_ADDRESS__)
// A trap inside a library call ends the process with exit code 1 and a message naming the command and
// the step, not with the shell's "Floating point exception" (exit 136). Each case runs in a child.
TEST(FatalSignalReportDeathTest, NamesTheCommandTheSignalAndTheStep) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  for (int signal : {SIGFPE, SIGSEGV}) {
    EXPECT_EXIT(
        {
          InstallFatalSignalReport("mesh");
          const CurrentStep running("surface: Poisson reconstruction (CGAL)");
          std::raise(signal);
        },
        ::testing::ExitedWithCode(1),
        std::string("cinepath mesh: internal error: ") + (signal == SIGFPE ? "SIGFPE" : "SIGSEGV") +
            ".* in step 'surface: Poisson reconstruction \\(CGAL\\)'; no output was written");
  }
}

// Without the report the same trap is the bare signal: the test above fails without the handler.
TEST(FatalSignalReportDeathTest, WithoutTheReportATrapIsABareSignal) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(std::raise(SIGFPE), ::testing::KilledBySignal(SIGFPE), "");
}
#endif

}  // namespace
}  // namespace cinepath
