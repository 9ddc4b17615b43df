// The ways through the wall-contact loop give the same bits: a grain's candidate triangles
// through the near elements (sim/near_wall_elements.hpp) or the whole list, and the linear law
// in SIMD lanes (contact/linear_batch.hpp) or contact by contact. A frictional, polydisperse
// pile settles into a still egg-crate mesh, where grains touch faces, convex and concave edges
// and vertices, several triangles at once, and hand their contacts from one triangle to the
// next.
#include "core/random.hpp"
#include "test_support.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

// A 10 x 10 floor of squares, each cut into two triangles, its vertices at
// z = -3 + 0.35 sin(1.3 x) sin(1.1 y).
MeshWall egg_crate() {
  const auto z = [](double x, double y) {
    return -3.0 + 0.35 * std::sin(1.3 * x) * std::sin(1.1 * y);
  };
  std::vector<std::array<Vec3, 3>> soup;
  const double edge = 0.8;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const double x0 = -4 + i * edge, y0 = -4 + j * edge, x1 = x0 + edge, y1 = y0 + edge;
      const Vec3 a{x0, y0, z(x0, y0)}, b{x1, y0, z(x1, y0)}, c{x1, y1, z(x1, y1)},
          d{x0, y1, z(x0, y1)};
      soup.push_back({a, b, c});
      soup.push_back({a, c, d});
    }
  MeshWall w;
  w.name = "floor";
  w.mesh = TriangleMesh::weld(soup);
  w.material = 1;
  return w;
}

// `unused_convention`: a third material, in no contact, whose pairs cap friction differently,
// so that the law cannot be batched (LinearBatch::prepare) and every contact goes one by one.
Simulation pile_on_mesh(double near_fraction, bool unused_convention) {
  Random rng(5);
  auto cfg = test::open_box(4.0, {0.1, 0.0, -1.0}, 5e-4);
  cfg.box.boundary = {Boundary::wall, Boundary::wall, Boundary::open};
  cfg.box.hi.z = 8.0;
  cfg.skin = 0.3;
  cfg.near_fraction = near_fraction;
  std::vector<ParticleSpec> specs;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 3; ++k)
        specs.push_back(test::sphere({-3.0 + 1.2 * i, -3.0 + 1.2 * j, -1.8 + 1.1 * k},
                                     rng.uniform(0.35, 0.5), 0.5,
                                     {rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 0},
                                     {rng.uniform(-1, 1), rng.uniform(-1, 1), 0}));
  const test::Coeffs c{5e3, 1.5e3, 50.0, 20.0, 0.6, 0.4};
  ContactLaw<LinearSpringDashpot> law{PairTable<test::Coeffs>(3)};
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = a; b < 3; ++b) law.coeffs.set(a, b, c);
  if (unused_convention) {
    test::Coeffs other = c;
    other.friction_cap = CapOn::total;
    law.coeffs.set(2, 2, other);
  }
  return Simulation(cfg, test::store_of(specs), {}, {}, law, Comm::self(), {egg_crate()});
}

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
  Simulation whole = pile_on_mesh(0.0, false), near = pile_on_mesh(0.25, false);
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
  Simulation batched = pile_on_mesh(0.25, false), one_by_one = pile_on_mesh(0.25, true);
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
