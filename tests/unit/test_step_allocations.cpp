// A step that builds no lists allocates nothing: the pair loop and the wall loop keep each
// contact's state in room made at the list build (contact/contact_history.hpp), never in memory
// they take. The pile of
// egg_crate_pile.hpp falls onto the mesh and settles, its contacts with each other and with the
// mesh opening and closing between list builds, through the SIMD batches and the one-by-one
// loop. Every allocation is counted (this binary replaces operator new).
#include "egg_crate_pile.hpp"

#include <atomic>
#include <cstdlib>
#include <gtest/gtest.h>
#include <new>

namespace {
std::atomic<long> allocations{0};
} // namespace

// (g++ cannot see that operator new below is malloc: it would warn at each delete inlined.)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t bytes) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(bytes == 0 ? 1 : bytes)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop

namespace yuxi {
namespace {

struct Counts {
  int quiet_steps = 0;   // steps with no list build and no pick of near pairs
  int opening_steps = 0; // of those, steps where more contacts touched than the step before
  long allocations = 0;  // made in those steps
  std::size_t most_wall_contacts = 0;
};

Counts count_allocations(Simulation sim, int steps) {
  Counts c;
  std::size_t touching = 0;
  for (int k = 0; k < steps; ++k) {
    const std::int64_t builds = sim.list_builds();
    const bool near_held = sim.near_pairs().picked;
    const long before = allocations.load();
    sim.step();
    const long made = allocations.load() - before;
    // Steps that build a list make room: a list build, and a pick of near pairs (it sets
    // their displacement bound to zero: core/near_pairs.hpp) or near pairs dropped.
    if (sim.list_builds() != builds || sim.near_pairs().moved == 0.0 ||
        (near_held && !sim.near_pairs().picked)) {
      touching = sim.last_tally().touching;
      continue;
    }
    ++c.quiet_steps;
    c.allocations += made;
    c.opening_steps += sim.last_tally().touching > touching ? 1 : 0;
    touching = sim.last_tally().touching;
    c.most_wall_contacts = std::max(c.most_wall_contacts, sim.shaped_wall_loads()[0].contacts);
  }
  return c;
}

TEST(StepAllocations, AStepWithoutAListBuildAllocatesNothing) {
  for (const bool one_by_one : {false, true}) {
    const Counts c = count_allocations(test::pile_on_mesh(0.25, one_by_one), 6000);
    EXPECT_GT(c.quiet_steps, 3000) << "one by one: " << one_by_one;
    EXPECT_GT(c.opening_steps, 100) << "one by one: " << one_by_one;
    EXPECT_GT(c.most_wall_contacts, 20u) << "one by one: " << one_by_one;
    EXPECT_EQ(c.allocations, 0) << "one by one: " << one_by_one;
  }
}

} // namespace
} // namespace yuxi
