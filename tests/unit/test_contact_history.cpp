// Contact history survives neighbour-list rebuilds: rebuilding (and re-sorting the particles)
// at any step leaves the trajectory unchanged, also for contacts whose tangential spring is
// loaded, sliding, or listed the other way round after the rebuild. Re-sorting changes the
// order in which contact forces are summed, so the runs agree to round-off (1e-9 here after
// 3000 steps), not bit for bit. Dropping the history at rebuilds instead moves the grains by
// 0.2 to 0.5 (measured), so the test is sharp.
#include "core/random.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

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

// A grain's contacts with a shaped wall: the first held in place, the others in a block made
// for them. Three contacts of one grain and one of another survive a rebuild that lists the
// grains the other way round, each state with its normal, in order; a copied set keeps its own.
TEST(ContactHistory, AGrainsWallContactsSurviveARebuildInOrder) {
  using State = LinearSpringDashpot::State;
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
  auto& three = history.wall[0];
  three.make_room(3);
  for (std::size_t c = 0; c < 3; ++c)
    three.at(c) = {{0, 0, 1.0 + static_cast<double>(c)}, state(1.0 + static_cast<double>(c))};
  three.n = 3;
  history.wall[1].at(0) = {{1, 0, 0}, state(9.0)};
  history.wall[1].n = 1;

  WallContactSet<State> copy = three;
  three.at(2).state = state(-1.0);
  EXPECT_EQ(copy.at(2).state, state(3.0));
  three.at(2).state = state(3.0);
  EXPECT_GT(history.memory_bytes(), history.wall_blocks_bytes());
  EXPECT_GT(history.wall_blocks_bytes(), 0u);

  history.stash(s, before);
  NeighborList after;
  after.walls = {{1, 0}, {0, 0}};
  history.restore(s, after);
  ASSERT_EQ(history.wall[1].n, 3u);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(history.wall[1].at(c).normal, (Vec3{0, 0, 1.0 + static_cast<double>(c)}));
    EXPECT_EQ(history.wall[1].at(c).state, state(1.0 + static_cast<double>(c)));
  }
  ASSERT_EQ(history.wall[0].n, 1u);
  EXPECT_EQ(history.wall[0].at(0).state, state(9.0));
  EXPECT_EQ(history.wall_blocks_bytes(), history.wall[1].block_bytes());
}

} // namespace
} // namespace yuxi
