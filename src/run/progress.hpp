// Progress of a run on the terminal (step, simulated time, steps/s, ETA), redrawn in place at
// most twice a second. Silent when standard error is not a terminal (CI, redirected logs).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

namespace yuxi {

class Progress {
public:
  using Sink = std::function<void(const std::string& line)>;
  Progress(std::int64_t first_step, std::int64_t last_step, bool enabled, Sink sink = {});
  void update(std::int64_t step, double time);
  void finish();
  static bool stderr_is_terminal();

private:
  using Clock = std::chrono::steady_clock;
  std::int64_t first_, last_;
  bool enabled_;
  Sink sink_;
  bool drawn_ = false;
  Clock::time_point start_, last_draw_;
};

} // namespace yuxi
