#include "progress.h"

#include <unistd.h>

#include <csignal>
#include <cstdio>

namespace crestline::cli {
namespace {

volatile std::sig_atomic_t interrupted = 0;

extern "C" void on_interrupt(int) { interrupted = 1; }

}  // namespace

Progress::Progress(bool enabled)
    : enabled_(enabled && isatty(fileno(stderr))), start_(Clock::now()), last_draw_(start_) {}

void Progress::catch_interrupt() { std::signal(SIGINT, on_interrupt); }

bool Progress::operator()(Stage stage, double fraction) {
  if (interrupted) return false;
  if (!enabled_) return true;
  const auto now = Clock::now();
  if (now - start_ < std::chrono::seconds(1)) return true;
  if (shown_ && now - last_draw_ < std::chrono::milliseconds(100)) return true;
  last_draw_ = now;
  shown_ = true;
  const double percent = 100.0 * (fraction < 0 ? 0 : fraction > 1 ? 1 : fraction);
  std::fprintf(stderr, "\r\033[Kcrestline: %s %3.0f%%", stage_name(stage), percent);
  std::fflush(stderr);
  return true;
}

void Progress::clear() {
  if (!shown_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace crestline::cli
