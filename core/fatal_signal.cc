#include "core/fatal_signal.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>

namespace cinepath {
namespace {

std::atomic<const char*> g_command{"cinepath"};
std::atomic<const char*> g_step{nullptr};

// Only async-signal-safe calls from here on: write(2) and _exit(2).
void Write(const char* text) {
  size_t left = std::strlen(text);
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, text, left);
    if (n <= 0) return;
    text += n;
    left -= static_cast<size_t>(n);
  }
}

const char* Describe(int signal) {
  switch (signal) {
    case SIGFPE: return "SIGFPE (an arithmetic trap: a division by zero)";
    case SIGSEGV: return "SIGSEGV (a read or write outside memory)";
    case SIGBUS: return "SIGBUS (a bad memory access)";
    case SIGILL: return "SIGILL (an illegal instruction)";
    default: return "a fatal signal";
  }
}

extern "C" void ReportFatalSignal(int signal) {
  Write("cinepath ");
  Write(g_command.load());
  Write(": internal error: ");
  Write(Describe(signal));
  const char* step = g_step.load();
  if (step != nullptr) {
    Write(" in step '");
    Write(step);
    Write("'");
  }
  Write("; no output was written. This is a bug in cinepath: please report it with the input that caused it.\n");
  ::_exit(1);
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAddressSanitizer = true;
#else
constexpr bool kAddressSanitizer = false;
#endif
#else
constexpr bool kAddressSanitizer = false;
#endif

}  // namespace

void InstallFatalSignalReport(const char* command) {
  g_command.store(command);
  if (kAddressSanitizer) return;
  struct sigaction action {};
  action.sa_handler = ReportFatalSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  for (int signal : {SIGFPE, SIGSEGV, SIGBUS, SIGILL}) sigaction(signal, &action, nullptr);
}

CurrentStep::CurrentStep(const char* step) : outer_(g_step.exchange(step)) {}
CurrentStep::~CurrentStep() { g_step.store(outer_); }

const char* RunningStep() { return g_step.load(); }

}  // namespace cinepath
