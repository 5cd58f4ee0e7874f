// Progress reporting for long stages: drawn on stderr only when stderr is a terminal (mode auto),
// never into pipes, logs or CI output, so golden tests see an empty stderr.
#pragma once

#include <chrono>
#include <string>

namespace cinepath {

enum class ProgressMode { kAuto, kAlways, kNever };

// "auto" | "always" | "never"; InputError otherwise.
ProgressMode ParseProgressMode(const std::string& text);

class Progress {
 public:
  Progress(std::string label, double total, ProgressMode mode = ProgressMode::kAuto);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  bool enabled() const { return enabled_; }
  void Update(double done);  // redraws at most ~10 times a second
  void Finish();             // final line, then newline

 private:
  void Draw(double done);
  std::string label_;
  double total_;
  bool enabled_;
  bool finished_ = false;
  double last_done_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace cinepath
