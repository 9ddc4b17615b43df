// The volume of a ball of radius r: 4/3 pi r^3.
#pragma once

#include "core/units.hpp"

namespace yuxi {

inline constexpr double ball_volume(double r) {
  return 4.0 / 3.0 * pi * r * r * r;
}

} // namespace yuxi
