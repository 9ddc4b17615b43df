#include "run/progress.hpp"

#include <algorithm>
#include <cstdio>
#include <fmt/format.h>
#include <unistd.h>

namespace yuxi {

bool Progress::stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

Progress::Progress(std::int64_t first_step, std::int64_t last_step, bool enabled, Sink sink)
    : first_(first_step), last_(last_step), enabled_(enabled), sink_(std::move(sink)),
      start_(Clock::now()), last_draw_(start_) {}

void Progress::update(std::int64_t step, double time) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(500) && step != last_) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double done = static_cast<double>(step - first_);
  const double rate = elapsed > 0 ? done / elapsed : 0.0;
  const double eta = rate > 0 ? static_cast<double>(last_ - step) / rate : 0.0;
  const auto eta_s = static_cast<long>(eta);
  const std::string line = fmt::format(
      "\r  step {}/{}  t = {:.4f}  {:.0f} steps/s  {:.1f}%  ETA {}:{:02d}:{:02d}   ", step, last_,
      time, rate, 100.0 * done / static_cast<double>(std::max<std::int64_t>(1, last_ - first_)),
      eta_s / 3600, (eta_s / 60) % 60, eta_s % 60);
  if (sink_) {
    sink_(line);
  } else {
    fmt::print(stderr, "{}", line);
    std::fflush(stderr);
  }
  drawn_ = true;
}

void Progress::finish() {
  if (drawn_) {
    if (sink_)
      sink_("\n");
    else
      fmt::print(stderr, "\n");
  }
  drawn_ = false;
}

} // namespace yuxi
