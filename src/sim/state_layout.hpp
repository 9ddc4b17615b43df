// The layout of a simulation's saved state (Simulation::save_state), which a checkpoint file's
// format version names (io/checkpoint_file.hpp): layout 6 added the sources' part; a state of
// layout 5 loads with no insert or outlet under way. Layout 7 added each servo's offset at the
// last list build; a state of layout 6 takes the offset it was saved with. Layout 8 names each
// insert and outlet with its progress (a branch matches them by name) and keeps the inserts'
// pourings started, paused or stopped from outside the scene; a state of layout 6 or 7 matches
// them by position. Layout 9 adds the linked cells' edge and the skin after the cut planes, so
// that a resumed run is built straight from its state with the saved run's cells; a state of
// layout 8 or older is given cells sized for its particles. Layout 10 adds the clumps' bodies
// (sim/clump_bodies.hpp) before the particles, and the particles' `body` field; in a state of
// layout 9 or older no particle is a clump's member. Layout 11 adds each insert's owed grains
// (their sizes and velocities) after the outlets' parts; in a state of layout 10 or older they
// are drawn afresh. Layout 12 adds the names of the scene's shapes after the clumps' bodies, so
// that a branch into a scene of other shapes finds each clump's shape by name; a state of layout
// 10 or 11 takes its clumps' shape indices to be those of the scene it is loaded under.
#pragma once

#include <cstdint>

namespace yuxi {

inline constexpr std::uint32_t state_layout = 12, oldest_state_layout = 5;

} // namespace yuxi
