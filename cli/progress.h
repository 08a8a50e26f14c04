#pragma once
// A one-line progress indicator on stderr. It appears only once the work has
// taken longer than a second, only on a terminal, and never with --quiet.
#include <chrono>

#include "crestline/pipeline.h"

namespace crestline::cli {

class Progress {
 public:
  explicit Progress(bool enabled);
  ~Progress() { clear(); }

  /// The pipeline's ProgressCallback. Returns false once SIGINT was received,
  /// which makes the pipeline throw Cancelled.
  bool operator()(Stage stage, double fraction);
  /// Removes the indicator line (before other output on stderr).
  void clear();

  /// Installs a SIGINT handler that turns Ctrl-C into a clean cancellation.
  static void catch_interrupt();

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  bool shown_ = false;
  Clock::time_point start_;
  Clock::time_point last_draw_;
};

}  // namespace crestline::cli
