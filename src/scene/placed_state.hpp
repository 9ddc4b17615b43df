// Where a point of a wall stands at some time, and how fast it moves there.
#pragma once

#include "core/vec3.hpp"

namespace yuxi {

struct PlacedState {
  Vec3 position;
  Vec3 velocity;
};

} // namespace yuxi
