// The settings of a simulation that a scene gives (the [domain] and [run] tables' engine part):
// the box and its boundaries, gravity, the time step, the neighbour search and the MPI layout.
// Apart from the engine, so that the scene layer (io/scene.hpp) names them without it.
#pragma once

#include "core/box.hpp"
#include "core/vec3.hpp"

#include <array>
#include <cstdint>

namespace yuxi {

// What to do with a grain that leaves the box through an open face.
enum class EscapePolicy { stop, remove };

// The load the cut planes of a multi-rank run balance (SimulationConfig::balance_by).
enum class BalanceBy { pairs, time };

// Where and how the forces are computed: `cpu`, the pair loop with the linear law's SIMD lanes
// where they apply; `cpu_reference`, every contact one by one through its law's evaluate(), the
// oracle the other backends are held to (tests/backend/test_every_backend.cpp).
enum class Backend { cpu, cpu_reference };

struct SimulationConfig {
  Box box;
  Vec3 gravity;
  double dt = 1e-4;
  double skin = 0.2;      // Verlet skin [length]
  double cell_size = 0.0; // linked-cell edge; 0 = the smallest valid (2 r_max + skin)
  EscapePolicy on_escape = EscapePolicy::stop;
  std::uint8_t box_wall_material = 0; // material of the flat walls on Boundary::wall faces
  double max_overlap_ratio = 1.0;     // stop if an overlap exceeds this times the smaller radius
  std::array<int, 3> ranks{0, 0, 0};  // MPI ranks per axis; 0 = chosen automatically
  int rebalance_every = 50;           // move the cut planes every this many list builds (0: never)
  // What the cut planes balance: each particle's count of listed pairs (the same cuts on every
  // run: reproducible to the bit), or the compute time each rank measured since the last
  // balancing (a rank on a slower or busier core gets less; the cuts, and so the round-off of
  // the sums, then differ from run to run).
  BalanceBy balance_by = BalanceBy::pairs;
  // The near pairs' margin as a fraction of the skin (core/near_pairs.hpp; 0: scan the whole
  // list every step). The trajectory is the same either way.
  double near_fraction = 0.25;
  // The linked cells are at least this wide beyond the skin: grains that come later
  // ([[insert]]) may be larger than any at the start [length].
  double min_contact_reach = 0.0;
  // The farthest a member's centre stands from its clump's centre of mass, over the clumps the
  // scene can hold (its fills and inserts of shapes, at their largest size) [length]: on
  // several ranks, how much farther the ghosts reach (sim/exchange.hpp). The engine takes at
  // least its clumps' own; a scene and its resumed run agree on it.
  double clump_reach = 0.0;
  Backend backend = Backend::cpu;
};

// Gravity's components along periodic axes (no potential: a grain that wraps around would jump
// in height; their work is booked apart) and along the others (docs/ARCHITECTURE.md, "Energy
// books").
inline Vec3 periodic_gravity(const SimulationConfig& c) {
  Vec3 g;
  for (int a = 0; a < 3; ++a)
    if (c.box.periodic(a)) g[a] = c.gravity[a];
  return g;
}
inline Vec3 potential_gravity(const SimulationConfig& c) {
  return c.gravity - periodic_gravity(c);
}

} // namespace yuxi
