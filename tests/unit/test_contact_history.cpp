// Contact history survives neighbour-list rebuilds: rebuilding (and re-sorting the particles)
// at any step leaves the trajectory unchanged, also for contacts whose tangential spring is
// loaded, sliding, or listed the other way round after the rebuild. Re-sorting changes the
// order in which contact forces are summed, so the runs agree to round-off (1e-9 here after
// 3000 steps), not bit for bit. Dropping the history at rebuilds instead moves the grains by
// 0.2 to 0.5 (measured), so the test is sharp.
#include "core/random.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <gtest/gtest.h>
#include <type_traits>

namespace yuxi {
namespace {

// A dense, frictional, polydisperse pile under gravity in a periodic-x, walled box.
Simulation pile() {
  Random rng(9);
  auto cfg = test::open_box(3.0, {0.3, 0.0, -1.0}, 2e-4);
  cfg.box.boundary = {Boundary::periodic, Boundary::wall, Boundary::wall};
  std::vector<ParticleSpec> specs;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 5; ++k)
        specs.push_back(test::sphere({-2.5 + i, -2.5 + j, -2.5 + k}, rng.uniform(0.4, 0.55), 0.5,
                                     {rng.uniform(-1, 1), rng.uniform(-1, 1), 0}));
  return Simulation(cfg, test::store_of(specs), {}, {},
                    test::linear_law({5e3, 1.5e3, 5.0, 2.0, 0.6, 0.4}));
}

std::vector<Vec3> positions_by_gid(const Simulation& sim) {
  const auto& s = sim.particles();
  std::vector<Vec3> x(s.n_owned());
  for (std::size_t i = 0; i < s.n_owned(); ++i) x[static_cast<std::size_t>(s.gid[i])] = s.x[i];
  return x;
}

TEST(ContactHistory, RebuildingAtAnyStepChangesNothingButRoundOff) {
  Simulation plain = pile(), rebuilt = pile();
  for (int k = 0; k < 3000; ++k) {
    if (k % 7 == 3) rebuilt.request_list_build();
    plain.step();
    rebuilt.step();
  }
  ASSERT_GT(rebuilt.list_builds(), plain.list_builds() + 300);
  ASSERT_GT(plain.last_tally().touching, 20u); // many loaded contacts carried through
  const auto a = positions_by_gid(plain), b = positions_by_gid(rebuilt);
  for (std::size_t g = 0; g < a.size(); ++g) EXPECT_LT(norm(a[g] - b[g]), 1e-9) << "grain " << g;
  EXPECT_NEAR(plain.energies().dissipated, rebuilt.energies().dissipated,
              1e-9 * plain.energies().dissipated);
}

TEST(ContactHistory, MirroredStateFollowsTheListedOrientation) {
  LinearSpringDashpot::State s;
  s.tangential = {.spring = {1, 2, 3}, .sliding = 1, .k = 7.0};
  s.rolling = {.spring = {4, 5, 6}, .sliding = 0, .k = 77.0};
  EXPECT_EQ(s.mirrored().tangential.spring, (Vec3{-1, -2, -3}));
  EXPECT_EQ(s.mirrored().tangential.sliding, 1u);
  EXPECT_EQ(s.mirrored().rolling.spring, (Vec3{4, 5, 6})); // -a (w_i - w_j) x n is symmetric
  EXPECT_EQ(s.mirrored().mirrored(), s);
}

// A grain's contacts with a shaped wall: the first in the candidate's record (of fixed size,
// no pointer), the others in a block taken from the room made at the list build. Three contacts
// of one grain and one of another survive a rebuild that lists the grains the other way round,
// each state with its normal, in order; taking a block moves no memory.
TEST(ContactHistory, AGrainsWallContactsSurviveARebuildInOrder) {
  using State = LinearSpringDashpot::State;
  static_assert(std::is_trivially_copyable_v<WallContactSet<State>>);
  const ParticleStore s =
      test::store_of({test::sphere({0, 0, 0}, 0.5, 1.0), test::sphere({2, 0, 0}, 0.5, 1.0)});
  const auto state = [](double x) {
    State st;
    st.tangential = {.spring = {x, 2 * x, 3 * x}, .sliding = 1, .k = x};
    return st;
  };
  NeighborList before;
  before.walls = {{0, 0}, {1, 0}};
  ContactHistory<State> history;
  history.restore(s, before);
  ASSERT_EQ(history.wall.size(), 2u);
  history.make_wall_room(0, 3);
  const auto* block = &history.wall_contact(0, 1);
  history.make_wall_room(1, 2); // the second candidate's block, from the same room
  history.make_wall_room(0, 3); // (it has one)
  EXPECT_EQ(&history.wall_contact(0, 1), block);
  for (std::size_t c = 0; c < 3; ++c)
    history.wall_contact(0, c) = {{0, 0, 1.0 + static_cast<double>(c)},
                                  state(1.0 + static_cast<double>(c))};
  history.wall[0].n = 3;
  history.wall_contact(1, 0) = {{1, 0, 0}, state(9.0)};
  history.wall[1].n = 1;

  history.stash(s, before);
  NeighborList after;
  after.walls = {{1, 0}, {0, 0}};
  history.restore(s, after);
  ASSERT_EQ(history.wall[1].n, 3u);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(history.wall_contact(1, c).normal, (Vec3{0, 0, 1.0 + static_cast<double>(c)}));
    EXPECT_EQ(history.wall_contact(1, c).state, state(1.0 + static_cast<double>(c)));
  }
  ASSERT_EQ(history.wall[0].n, 1u);
  EXPECT_EQ(history.wall_contact(0, 0).state, state(9.0));
  EXPECT_EQ(history.wall[0].block, WallContactSet<State>::no_block); // one contact: no block
}

// The room for the slots is made at the list build: opening and closing contacts, over and over,
// moves no memory, the slots given back being taken again. A state stashed at a list build comes
// back to its pair, mirrored where the pair is listed the other way round.
TEST(ContactHistory, OpeningContactsMovesNoMemory) {
  using State = LinearSpringDashpot::State;
  const ParticleStore s =
      test::store_of({test::sphere({0, 0, 0}, 0.5, 1.0), test::sphere({0.9, 0, 0}, 0.5, 1.0),
                      test::sphere({0, 0.9, 0}, 0.5, 1.0)});
  // A list of 200 pairs (the same two, over and over: the slots do not care).
  NeighborList crowded;
  crowded.offsets = {0, 200, 200, 200};
  for (std::uint32_t p = 0; p < 200; ++p) crowded.partners.push_back(1 + p % 2);
  crowded.index_rows();
  ContactHistory<State> history;
  history.restore(s, crowded);
  ASSERT_GE(history.states.capacity(), 200u);
  const State* room = history.states.data();
  for (int round = 0; round < 3; ++round) {
    for (std::uint32_t p = round; p < 200; ++p) { // (a different first pair each round)
      State& st = history.open(p);
      EXPECT_EQ(st, State{}) << "pair " << p; // opened fresh, whatever the slot held before
      st.tangential.spring = {1.0 + p, 2.0, 3.0};
      EXPECT_EQ(&history.state_of(p), &st);
    }
    for (std::uint32_t p = 0; p < 200; ++p)
      if (history.pair_slot[p] != history.none) history.close(p);
    EXPECT_EQ(std::count(history.pair_slot.begin(), history.pair_slot.end(), history.none), 200);
  }
  EXPECT_EQ(history.states.data(), room);
  EXPECT_EQ(history.states.size(), 200u); // no more slots than contacts at once

  NeighborList before;
  before.offsets = {0, 2, 2, 2};
  before.partners = {1, 2};
  before.index_rows();
  history.restore(s, before);
  history.open(1).tangential.spring = {4, 5, 6}; // the pair (0, 2)
  history.stash(s, before);
  NeighborList after; // (2, 0) listed from particle 2, (0, 1) from 0
  after.offsets = {0, 1, 1, 2};
  after.partners = {1, 0};
  after.index_rows();
  history.restore(s, after);
  EXPECT_EQ(history.pair_slot[0], history.none); // (0, 1) held nothing: it stays closed
  ASSERT_NE(history.pair_slot[1], history.none);
  EXPECT_EQ(history.state_of(1).tangential.spring, (Vec3{-4, -5, -6}));
}

} // namespace
} // namespace yuxi
