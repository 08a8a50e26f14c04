#pragma once
// A one-line progress indicator on stderr. It appears only once the work has
// taken longer than a second, only on a terminal, and never with --quiet.
// A ticker thread redraws it, so a long stage that reports no fractions
// still shows that it is alive (with the elapsed seconds).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "crestline/pipeline.h"

namespace crestline::cli {

class Progress {
 public:
  explicit Progress(bool enabled);
  ~Progress() { stop(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Names the current step outside the pipeline ("reading", "writing").
  void phase(const char* label);
  /// The pipeline's ProgressCallback. Returns false once SIGINT was received,
  /// which makes the pipeline throw Cancelled.
  bool operator()(Stage stage, double fraction);
  /// Writes one line to stderr without tearing the indicator line.
  void print(const std::string& line);
  /// Stops the ticker and removes the indicator line (before other output).
  void stop();

  /// Installs a SIGINT handler that turns Ctrl-C into a clean cancellation.
  static void catch_interrupt();

 private:
  void tick();

  using Clock = std::chrono::steady_clock;
  const Clock::time_point start_ = Clock::now();
  std::atomic<const char*> label_{"reading"};
  std::atomic<double> fraction_{-1};  // negative: unknown
  bool shown_ = false;
  bool stopping_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread ticker_;
};

}  // namespace crestline::cli
