// The cell-based neighbour list equals an O(N^2) brute force over minimum images, on random
// polydisperse systems in open and periodic boxes (issue: neighbour search tests).
#include "core/random.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <set>

namespace yuxi {
namespace {

using PairSet = std::set<std::pair<GlobalId, GlobalId>>;

PairSet listed_pairs(const Simulation& sim) {
  const auto& s = sim.particles();
  const auto& l = sim.neighbor_list();
  PairSet out;
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    for (auto p = l.offsets[i]; p < l.offsets[i + 1]; ++p) {
      const GlobalId a = s.gid[i], b = s.gid[l.partners[p]];
      const bool fresh = out.emplace(std::min(a, b), std::max(a, b)).second;
      EXPECT_TRUE(fresh) << "pair " << a << "-" << b << " listed twice";
    }
  return out;
}

// Every pair closer than r_i + r_j + range, through the nearest periodic image.
PairSet brute_force(const Simulation& sim, double range) {
  const auto& s = sim.particles();
  const Box& box = sim.config().box;
  PairSet out;
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    for (std::size_t j = i + 1; j < s.n_owned(); ++j) {
      if (!s.is_grain(i) && !s.is_grain(j)) continue;
      const double cut = s.radius[i] + s.radius[j] + range;
      if (norm2(box.minimum_image(s.x[i], s.x[j])) < cut * cut)
        out.emplace(std::min(s.gid[i], s.gid[j]), std::max(s.gid[i], s.gid[j]));
    }
  return out;
}

Simulation random_system(bool periodic, std::uint64_t seed, int n, double walls_fraction) {
  Random rng(seed);
  auto cfg = test::open_box(6.0, {}, 1e-4);
  cfg.skin = 0.25;
  if (periodic) cfg.box.boundary = {Boundary::periodic, Boundary::periodic, Boundary::periodic};
  std::vector<ParticleSpec> specs;
  for (int k = 0; k < n; ++k) {
    auto p = test::sphere({rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(-6, 6)},
                          rng.uniform(0.3, 0.9), 1.0);
    if (rng.uniform() < walls_fraction) p.kind = Kind::wall;
    specs.push_back(p);
  }
  // Dense random packings overlap heavily; forces are irrelevant here, so no overlap limit.
  cfg.max_overlap_ratio = 1e9;
  return Simulation(cfg, test::store_of(specs), {}, {}, test::linear_law({1e3, 0, 0, 0, 0, 0}));
}

class NeighborSearch : public ::testing::TestWithParam<std::tuple<bool, int>> {};

TEST_P(NeighborSearch, EqualsBruteForce) {
  const auto [periodic, seed] = GetParam();
  Simulation sim = random_system(periodic, static_cast<std::uint64_t>(seed), 600, 0.2);
  const PairSet expected = brute_force(sim, sim.config().skin);
  const PairSet listed = listed_pairs(sim);
  EXPECT_GT(expected.size(), 500u); // the test means something
  EXPECT_EQ(listed, expected);
}

INSTANTIATE_TEST_SUITE_P(OpenAndPeriodic, NeighborSearch,
                         ::testing::Combine(::testing::Bool(), ::testing::Values(1, 2, 3)));

TEST(NeighborSearch, StaysCompleteAfterParticlesMoveAndTheListIsRebuilt) {
  Simulation sim = random_system(true, 11, 400, 0.0);
  auto& s = sim.particles_mutable();
  Random rng(5);
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    s.x[i] += Vec3{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
  sim.refresh(); // wraps into the periodic box and rebuilds
  EXPECT_EQ(listed_pairs(sim), brute_force(sim, sim.config().skin));
}

} // namespace
} // namespace yuxi
