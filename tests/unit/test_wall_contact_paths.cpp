// The ways through the wall-contact loop give the same bits: a grain's candidate triangles
// through the near elements (sim/near_wall_elements.hpp) or the whole list, and the linear law
// in SIMD lanes (contact/linear_batch.hpp) or contact by contact. A frictional, polydisperse
// pile settles into a still egg-crate mesh, where grains touch faces, convex and concave edges
// and vertices, several triangles at once, and hand their contacts from one triangle to the
// next.
#include "egg_crate_pile.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

void expect_same_bits(const Simulation& a, const Simulation& b) {
  const auto& p = a.particles();
  const auto& q = b.particles();
  ASSERT_EQ(p.n_owned(), q.n_owned());
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    EXPECT_EQ(p.x[i], q.x[i]) << "particle " << p.gid[i];
    EXPECT_EQ(p.v[i], q.v[i]) << "particle " << p.gid[i];
    EXPECT_EQ(p.w[i], q.w[i]) << "particle " << p.gid[i];
  }
  EXPECT_EQ(a.energies().dissipated, b.energies().dissipated);
  EXPECT_EQ(a.energies().elastic, b.energies().elastic);
  EXPECT_EQ(a.shaped_wall_loads()[0].force, b.shaped_wall_loads()[0].force);
  EXPECT_EQ(a.shaped_wall_loads()[0].torque, b.shaped_wall_loads()[0].torque);
}

TEST(WallContactPaths, NearElementsChangeNothing) {
  Simulation whole = test::pile_on_mesh(0.0, false), near = test::pile_on_mesh(0.25, false);
  int reused = 0;           // steps whose search went through near elements picked before
  std::size_t fewest = ~0u; // the fewest near elements against the listed candidates
  std::size_t most_contacts = 0;
  for (int k = 0; k < 6000; ++k) {
    whole.step();
    near.step();
    ASSERT_FALSE(whole.near_wall_elements().picked && whole.near_pairs().hold());
    if (near.near_pairs().hold() && near.near_wall_elements().picked &&
        near.near_pairs().moved > 0) {
      ++reused;
      fewest = std::min(fewest, near.near_wall_elements().elements.size());
    }
    most_contacts = std::max(most_contacts, near.shaped_wall_loads()[0].contacts);
  }
  EXPECT_GT(reused, 1000);
  EXPECT_LT(fewest, near.neighbor_list().wall_elements.size());
  EXPECT_GT(most_contacts, 20u); // the pile rests on the floor
  expect_same_bits(whole, near);
}

TEST(WallContactPaths, BatchesAndTheOneByOneLoopAgree) {
  Simulation batched = test::pile_on_mesh(0.25, false), one_by_one = test::pile_on_mesh(0.25, true);
  int opened = 0; // steps where fewer grains touched the mesh than the step before
  std::size_t before = 0;
  for (int k = 0; k < 6000; ++k) {
    batched.step();
    one_by_one.step();
    // Each step's sums, in which the order of the terms shows.
    const ContactTally &a = batched.last_tally(), &b = one_by_one.last_tally();
    ASSERT_EQ(a.dissipated, b.dissipated) << "step " << k;
    ASSERT_EQ(a.elastic, b.elastic) << "step " << k;
    ASSERT_EQ(a.touching, b.touching) << "step " << k;
    const std::size_t now = batched.shaped_wall_loads()[0].contacts;
    opened += now < before ? 1 : 0;
    before = now;
  }
  EXPECT_GT(opened, 10); // contacts opened, releasing their springs' energy
  EXPECT_GT(batched.shaped_wall_loads()[0].contacts, 20u);
  expect_same_bits(batched, one_by_one);
}

} // namespace
} // namespace yuxi
