#include "progress.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>

namespace crestline::cli {
namespace {

volatile std::sig_atomic_t interrupted = 0;

// The pipeline checks for cancellation between stages only; a second Ctrl-C
// quits at once (no output exists yet before the final rename anyway).
extern "C" void on_interrupt(int) {
  interrupted = 1;
  static const char message[] = "\ncrestline: stopping after this stage (Ctrl-C again to quit now)\n";
  if (write(STDERR_FILENO, message, sizeof message - 1) < 0) {
  }
  std::signal(SIGINT, SIG_DFL);
}

}  // namespace

Progress::Progress(bool enabled) {
#ifdef __EMSCRIPTEN__
  (void)enabled;  // the WASM build of this command has no threads: no ticker
#else
  if (enabled && isatty(fileno(stderr))) ticker_ = std::thread([this] { tick(); });
#endif
}

void Progress::catch_interrupt() { std::signal(SIGINT, on_interrupt); }

void Progress::phase(const char* label) {
  label_ = label;
  fraction_ = -1;
}

bool Progress::operator()(Stage stage, double fraction) {
  label_ = stage_name(stage);
  fraction_ = fraction < 0 ? 0 : fraction > 1 ? 1 : fraction;
  return !interrupted;
}

void Progress::tick() {
  std::unique_lock<std::mutex> lock(mutex_);
  // Nothing for the first second: short runs stay silent.
  if (wake_.wait_for(lock, std::chrono::seconds(1), [this] { return stopping_; })) return;
  do {
    const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    const double fraction = fraction_;
    if (fraction >= 0)
      std::fprintf(stderr, "\r\033[Kcrestline: %s %3.0f%% (%.0f s)", label_.load(), 100 * fraction, seconds);
    else
      std::fprintf(stderr, "\r\033[Kcrestline: %s (%.0f s)", label_.load(), seconds);
    std::fflush(stderr);
    shown_ = true;
  } while (!wake_.wait_for(lock, std::chrono::milliseconds(200), [this] { return stopping_; }));
}

void Progress::print(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::fprintf(stderr, "%s%s\n", shown_ ? "\r\033[K" : "", line.c_str());
  std::fflush(stderr);
}

void Progress::stop() {
  if (!ticker_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  ticker_.join();
  if (shown_) {
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }
}

}  // namespace crestline::cli
