// A seeded random source whose numbers are the same on every platform and standard library.
// std::mt19937_64 is specified bit for bit, but std::normal_distribution and
// std::uniform_real_distribution are not (their algorithms are implementation-defined), so a
// scene built from a seed would differ between compilers; these two transforms are fixed here.
#pragma once

#include "core/units.hpp"

#include <cmath>
#include <cstdint>
#include <random>

namespace yuxi {

class Random {
public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Standard normal deviate (Box-Muller, one of the pair).
  double normal() {
    const double u1 = 1.0 - uniform(); // (0, 1]
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * pi * u2);
  }

  std::mt19937_64& engine() { return engine_; }

private:
  std::mt19937_64 engine_;
};

} // namespace yuxi
