// The times between which a wall exists: a silo's shutter until it opens, a lid from the
// moment it closes. Outside the window the wall touches nothing.
#pragma once

#include <limits>

namespace yuxi {

struct ActiveWindow {
  double from = -std::numeric_limits<double>::infinity(); // [time]
  double until = std::numeric_limits<double>::infinity(); // [time]
  bool at(double t) const { return t >= from && t < until; }
};

} // namespace yuxi
