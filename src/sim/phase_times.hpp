// Wall-clock seconds a simulation spends in each phase of its steps, and the scoped timer that
// adds a span to one of them.
#pragma once

#include <chrono>

namespace yuxi {

struct PhaseTimes {
  double integrate = 0, neighbor = 0, pair = 0, comm = 0;
  // The part of `neighbor` this rank spends on its own work (sorting, binning, the lists, the
  // contact states), without the list build's exchanges and waits for other ranks.
  double neighbor_local = 0;
  double total() const { return integrate + neighbor + pair + comm; }
  // What balancing by time evens out: the time a rank computes, waiting for no other.
  double busy() const { return pair + neighbor_local + integrate; }
};

// Adds the seconds from its construction to its end (or to the next switch_to()) to one of the
// phase times.
class PhaseTimer {
public:
  using Clock = std::chrono::steady_clock;
  explicit PhaseTimer(double& seconds) : seconds_(&seconds), start_(Clock::now()) {}
  ~PhaseTimer() { stop(); }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;
  // Books the span so far and goes on timing into `seconds`.
  void switch_to(double& seconds) {
    stop();
    seconds_ = &seconds;
    start_ = Clock::now();
  }

private:
  void stop() {
    const Clock::time_point now = Clock::now();
    *seconds_ += std::chrono::duration<double>(now - start_).count();
    start_ = now;
  }
  double* seconds_;
  Clock::time_point start_;
};

} // namespace yuxi
