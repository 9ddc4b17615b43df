// The largest centre distance at which two listed particles can touch.
#pragma once

#include "core/particle_store.hpp"

#include <algorithm>

namespace yuxi {

// Grain-grain or grain-wall (wall-wall pairs are never listed), over the owned particles.
inline double contact_reach(const ParticleStore& s) {
  double grain = 0.0, wall = 0.0;
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    double& largest = s.is_grain(i) ? grain : wall;
    largest = std::max(largest, s.radius[i]);
  }
  return std::max(2.0 * grain, grain + wall);
}

} // namespace yuxi
