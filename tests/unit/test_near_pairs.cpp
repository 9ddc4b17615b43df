// The near pairs (core/near_pairs.hpp) stand for the Verlet list in the overlap test: they hold
// the pairs closer than r_i + r_j + margin and those with a contact state, and scanning them
// instead of the whole list changes nothing, to the bit. Where the ghost pairs are computed
// apart (first), the near pairs keep them apart.
#include "core/near_pairs.hpp"
#include "core/random.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

namespace yuxi {
namespace {

TEST(NearPairs, KeepThePairsWithinTheMarginAndThoseInContact) {
  // Five spheres of radius 0.5 on the x axis; the list holds the pairs (0, k).
  const std::vector<Vec3> x{{0, 0, 0}, {0.9, 0, 0}, {1.04, 0, 0}, {1.2, 0, 0}, {0, 1.3, 0}};
  const std::vector<double> radius(5, 0.5);
  NeighborList list;
  list.offsets = {0, 4, 4, 4, 4, 4};
  list.partners = {1, 2, 3, 4};
  list.index_rows();
  // gaps: -0.1 (touching), 0.04, 0.2, 0.3; the last pair still holds a contact state
  const std::vector<std::uint32_t> slot{no_slot, no_slot, no_slot, 7};
  NearPairs near;
  pick_near_pairs(x.data(), radius.data(), list, slot.data(), 0.05, near);
  EXPECT_EQ(near.pairs, (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_TRUE(near.hold());
  near.moved = 0.024;
  EXPECT_TRUE(near.hold()); // both partners may have closed 0.048 of a 0.05 gap
  near.moved = 0.025;
  EXPECT_FALSE(near.hold());
}

TEST(NearPairs, ComeGhostPairsFirstWhereTheListHasThemApart) {
  // The same spheres, the first three owned and the last two ghosts.
  const std::vector<Vec3> x{{0, 0, 0}, {0.9, 0, 0}, {1.04, 0, 0}, {1.2, 0, 0}, {0, 1.3, 0}};
  const std::vector<double> radius(5, 0.5);
  NeighborList list;
  list.offsets = {0, 4, 4, 4};
  list.partners = {1, 2, 3, 4};
  list.index_rows();
  list.index_ghost_pairs(true);
  EXPECT_EQ(list.ghost_pairs, (std::vector<std::uint32_t>{2, 3}));
  const std::vector<std::uint32_t> slot{no_slot, no_slot, no_slot, 7};
  NearPairs near;
  pick_near_pairs(x.data(), radius.data(), list, slot.data(), 0.05, near);
  EXPECT_EQ(near.pairs, (std::vector<std::uint32_t>{3, 0, 1}));
  EXPECT_EQ(near.n_ghost, 1u);
  list.index_ghost_pairs(false); // one rank: list order
  EXPECT_TRUE(list.ghost_pairs.empty());
  pick_near_pairs(x.data(), radius.data(), list, slot.data(), 0.05, near);
  EXPECT_EQ(near.pairs, (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_EQ(near.n_ghost, 0u);
}

// A frictional, polydisperse pile settling under gravity in a box with a periodic axis: slow
// enough that the near pairs last many steps, with contacts opening and closing throughout.
Simulation settling_pile(double near_fraction) {
  Random rng(41);
  auto cfg = test::open_box(4.0, {0.2, 0.0, -1.0}, 5e-4);
  cfg.box.boundary = {Boundary::periodic, Boundary::wall, Boundary::wall};
  cfg.skin = 0.3;
  cfg.near_fraction = near_fraction;
  std::vector<ParticleSpec> specs;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 6; ++k)
        specs.push_back(test::sphere({-3.5 + i, -3.5 + j, -3.5 + k}, rng.uniform(0.4, 0.5), 0.5,
                                     {rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), 0}));
  return Simulation(cfg, test::store_of(specs), {}, {},
                    test::linear_law({5e3, 1.5e3, 50.0, 20.0, 0.6, 0.4}));
}

TEST(NearPairs, ScanningThemChangesNothing) {
  Simulation whole = settling_pile(0.0), near = settling_pile(0.25);
  int reused = 0; // steps that scanned near pairs picked at an earlier step
  std::size_t fewest = near.neighbor_list().n_pairs();
  for (int k = 0; k < 8000; ++k) {
    whole.step();
    near.step();
    ASSERT_FALSE(whole.near_pairs().hold());
    if (near.near_pairs().hold() && near.near_pairs().moved > 0) {
      ++reused;
      fewest = std::min(fewest, near.near_pairs().pairs.size());
    }
  }
  // Near pairs picked steps before were scanned most of the time (the displacement bound let
  // them), and they were fewer than the listed pairs.
  EXPECT_GT(reused, 4000);
  EXPECT_LT(fewest, near.neighbor_list().n_pairs());
  ASSERT_GT(near.last_tally().touching, 100u);
  const auto& a = whole.particles();
  const auto& b = near.particles();
  ASSERT_EQ(a.n_owned(), b.n_owned());
  for (std::size_t i = 0; i < a.n_owned(); ++i) {
    EXPECT_EQ(a.x[i], b.x[i]) << "particle " << a.gid[i];
    EXPECT_EQ(a.v[i], b.v[i]) << "particle " << a.gid[i];
    EXPECT_EQ(a.w[i], b.w[i]) << "particle " << a.gid[i];
  }
  EXPECT_EQ(whole.energies().dissipated, near.energies().dissipated);
  EXPECT_EQ(whole.energies().elastic, near.energies().elastic);
}

} // namespace
} // namespace yuxi
