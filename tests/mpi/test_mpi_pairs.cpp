// The distributed engine gives the answers of the serial one (tests/mpi/, run with mpirun -np
// 1, 2 and 4 by ctest): the session, the pair list and its ghosts, migration,
// the layout of the cut planes.
#include "mpi_support.hpp"

#include <gtest/gtest.h>

namespace yuxi {
namespace {

using namespace mpi_test;

// Where forces on ghosts go back to another rank, the pairs with a ghost are computed first
// and the rest while those forces travel (simulation.cpp: compute_forces()); the near pairs
// keep the two apart, so scanning them instead of the whole list still changes nothing, to the
// bit, on every rank: through the one-by-one law (rolling) and the SIMD batches.
// A session opened where MPI runs already (a host such as mpi4py started it: here the tests'
// own session) joins it: it sees the same job, and leaves MPI running when it ends.
TEST(Mpi, ASessionJoinsTheMpiItsHostStarted) {
  const Comm before = Comm::world();
  {
    const MpiSession joined;
    EXPECT_FALSE(joined.started_here());
    EXPECT_EQ(joined.world().size(), before.size());
    EXPECT_EQ(joined.world().rank(), before.rank());
  }
  int finalized = 1;
  MPI_Finalized(&finalized);
  EXPECT_EQ(finalized, 0);
  EXPECT_EQ(Comm::world().sum(std::int64_t{1}), before.size()); // still usable
}

TEST(Mpi, NearPairsChangeNothingWithTheGhostPairsFirst) {
  for (const bool rolling : {true, false}) {
    Simulation whole = dense(Comm::world(), 0.0, rolling);
    Simulation near = dense(Comm::world(), 0.25, rolling);
    int reused = 0;
    for (int k = 0; k < 1500; ++k) {
      whole.step();
      near.step();
      reused += near.near_pairs().hold() && near.near_pairs().moved > 0 ? 1 : 0;
    }
    EXPECT_GT(Comm::world().sum(static_cast<std::int64_t>(reused)), 300 * Comm::world().size());
    if (Comm::world().size() > 1) {
      EXPECT_FALSE(near.neighbor_list().ghost_pairs.empty());
    }
    const auto& a = whole.particles();
    const auto& b = near.particles();
    ASSERT_EQ(a.n_owned(), b.n_owned());
    for (std::size_t i = 0; i < a.n_owned(); ++i) {
      ASSERT_EQ(a.x[i], b.x[i]) << "particle " << a.gid[i] << (rolling ? ", rolling" : "");
      ASSERT_EQ(a.v[i], b.v[i]) << "particle " << a.gid[i] << (rolling ? ", rolling" : "");
      ASSERT_EQ(a.w[i], b.w[i]) << "particle " << a.gid[i] << (rolling ? ", rolling" : "");
    }
  }
}

TEST(Mpi, DensePackingMatchesTheSerialRun) {
  // Cut planes balanced by listed pairs (the default), and by measured time at every list
  // build: planes that move by the machine's timings, particles and springs with them.
  for (const BalanceBy by : {BalanceBy::pairs, BalanceBy::time}) {
    Simulation parallel = dense(Comm::world(), 0.25, true, by);
    parallel.run(400);
    const Snapshot a = snapshot(parallel);
    if (Comm::world().rank() == 0) {
      Simulation serial = dense(Comm::self());
      serial.run(400);
      EXPECT_GT(serial.energies().contacts, 150u); // a packing in contact, not a gas
      expect_same(a, snapshot(serial), 1e-9, 1e-7);
    }
  }
}

// The ownership rule (domain/halo.hpp): of every pair within the list's range, exactly one rank
// lists it, the one that holds the other particle in its half shell of ghosts; across the cut
// planes and the periodic boundaries alike. A full shell of ghosts would list pairs across
// ranks twice; a shell too thin, or a relay dropped at an edge, would miss some.
TEST(Mpi, EveryPairIsListedOnceOverAllRanks) {
  // Spheres anywhere in a box periodic along all three axes (overlaps allowed: only the list
  // matters here), a fifth of them wall particles, whose pairs are never listed.
  Random rng(29);
  auto cfg = test::open_box(6.0, {}, 1e-4);
  cfg.box.boundary = {Boundary::periodic, Boundary::periodic, Boundary::periodic};
  cfg.skin = 0.2;
  cfg.max_overlap_ratio = 1e9;
  std::vector<ParticleSpec> specs;
  for (int k = 0; k < 1500; ++k) {
    auto p = test::sphere({rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(-6, 6)},
                          rng.uniform(0.3, 0.6), 1.0);
    if (rng.uniform() < 0.2) p.kind = Kind::wall;
    specs.push_back(p);
  }
  const Simulation sim(cfg, test::store_of(specs), {}, {}, test::linear_law({1e3, 0, 0, 0, 0, 0}),
                       Comm::world());
  const auto& s = sim.particles();
  const auto& list = sim.neighbor_list();
  // The halo's count of copies of other ranks' particles (what the log's halo line reports):
  // the ghosts whose particle this rank does not own; the rest are its own periodic images.
  std::set<GlobalId> own(s.gid.begin(), s.gid.begin() + static_cast<std::ptrdiff_t>(s.n_owned()));
  std::size_t copies = 0;
  for (std::size_t g = s.n_owned(); g < s.size(); ++g) copies += own.count(s.gid[g]) == 0;
  EXPECT_EQ(sim.halo().n_ghosts_from_other_ranks(), copies);
  EXPECT_EQ(sim.comm().size() > 1, sim.comm().sum(static_cast<std::int64_t>(copies)) > 0);
  EXPECT_GT(s.n_ghost(), copies); // (periodic images along the axes one rank spans)
  std::vector<double> gids;       // (lower, higher) global id of each listed pair
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    for (auto p = list.offsets[i]; p < list.offsets[i + 1]; ++p) {
      const GlobalId a = s.gid[i], b = s.gid[list.partners[p]];
      gids.insert(gids.end(),
                  {static_cast<double>(std::min(a, b)), static_cast<double>(std::max(a, b))});
    }
  ArchiveWriter out;
  out.vector(gids);
  const auto parts = sim.comm().gather(out.data());
  const ParticleStore all = sim.gather_particles(); // collective
  if (!sim.comm().root()) return;
  std::map<std::pair<GlobalId, GlobalId>, int> listed;
  for (const auto& part : parts) {
    ArchiveReader in(part);
    std::vector<double> v;
    in.vector(v);
    for (std::size_t k = 0; k + 1 < v.size(); k += 2)
      ++listed[{static_cast<GlobalId>(v[k]), static_cast<GlobalId>(v[k + 1])}];
  }
  std::map<std::pair<GlobalId, GlobalId>, int> expected;
  const double range = sim.config().skin;
  for (std::size_t i = 0; i < all.n_owned(); ++i)
    for (std::size_t j = i + 1; j < all.n_owned(); ++j) {
      if (!all.is_grain(i) && !all.is_grain(j)) continue;
      const double cut = all.radius[i] + all.radius[j] + range;
      if (norm2(sim.config().box.minimum_image(all.x[i], all.x[j])) < cut * cut)
        expected[{std::min(all.gid[i], all.gid[j]), std::max(all.gid[i], all.gid[j])}] = 1;
    }
  EXPECT_GT(expected.size(), 3000u);
  int across = 0; // pairs through a periodic boundary: the test covers the images too
  for (std::size_t i = 0; i < all.n_owned(); ++i)
    for (std::size_t j = i + 1; j < all.n_owned(); ++j) {
      const double cut = all.radius[i] + all.radius[j] + range;
      across += norm2(all.x[i] - all.x[j]) >= cut * cut &&
                norm2(sim.config().box.minimum_image(all.x[i], all.x[j])) < cut * cut &&
                (all.is_grain(i) || all.is_grain(j));
    }
  EXPECT_GT(across, 100);
  EXPECT_EQ(listed, expected);
}

// Per-grain elastic energy (half of each contact's to each partner; the analysis of Figs. 8-10):
// over all particles it adds up to the engine's total less the flat walls' halves, and each
// particle's share is the serial run's, whichever rank computed its contacts.
TEST(Mpi, PerParticleElasticEnergyMatchesTheTotalAndTheSerialRun) {
  const auto shares = [](Simulation& sim) {
    sim.record_contacts(true);
    sim.run(300);
    const std::vector<double> e = particle_elastic_energy(sim); // collective
    double sum[2] = {0, 0};
    for (double x : e) sum[0] += x;
    const ContactRecord& record = sim.contact_record();
    for (std::size_t k = 0; k < record.plane_elastic.size(); ++k)
      if (record.holds_plane(k)) sum[1] += 0.5 * record.plane_elastic[k];
    sim.comm().sum(sum, 2);
    EXPECT_GT(sum[0], 0.0);
    EXPECT_NEAR(sum[0] + sum[1], sim.energies().elastic, 1e-9 * sum[0]);
    ArchiveWriter out;
    std::vector<double> pairs;
    for (std::size_t i = 0; i < e.size(); ++i)
      pairs.insert(pairs.end(), {static_cast<double>(sim.particles().gid[i]), e[i]});
    out.vector(pairs);
    std::map<GlobalId, double> by_gid;
    for (const auto& part : sim.comm().gather(out.data())) {
      ArchiveReader in(part);
      std::vector<double> v;
      in.vector(v);
      for (std::size_t k = 0; k + 1 < v.size(); k += 2)
        by_gid[static_cast<GlobalId>(v[k])] = v[k + 1];
    }
    return by_gid;
  };
  Simulation parallel = dense(Comm::world());
  const auto a = shares(parallel);
  if (Comm::world().rank() != 0) return;
  Simulation serial = dense(Comm::self());
  const auto b = shares(serial);
  ASSERT_EQ(a.size(), b.size());
  double worst = 0, scale = 0;
  for (const auto& [gid, e] : b) {
    worst = std::max(worst, std::abs(a.at(gid) - e));
    scale = std::max(scale, e);
  }
  EXPECT_LT(worst, 1e-6 * scale);
}

// Newton's third law across ranks: contact forces summed over all particles cancel, leaving
// gravity (no walls in this variant).
TEST(Mpi, ReverseSummedForcesCancel) {
  Random rng(3);
  auto cfg = test::open_box(5.0, {0, 0, -1.0}, 1e-4);
  cfg.box.boundary = {Boundary::periodic, Boundary::periodic, Boundary::periodic};
  std::vector<ParticleSpec> specs;
  for (int n = 0; n < 1500; ++n) {
    const double r = rng.uniform(0.3, 0.5);
    specs.push_back(
        test::sphere({rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)}, r, r * r * r));
  }
  cfg.max_overlap_ratio = 1e9;
  Simulation sim(cfg, test::store_of(specs), {}, {}, test::linear_law({1e3, 3e2, 0, 0, 0.5, 0.5}));
  sim.run(3);
  const auto& s = sim.particles();
  double f[3] = {0, 0, 0}, weight = 0;
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    f[0] += s.f[i].x, f[1] += s.f[i].y, f[2] += s.f[i].z;
    weight += s.mass[i];
  }
  sim.comm().sum(f, 3);
  weight = sim.comm().sum(weight);
  ASSERT_GT(sim.energies().contacts, 1000u);
  EXPECT_NEAR(f[0], 0.0, 1e-8 * weight * 1e3);
  EXPECT_NEAR(f[1], 0.0, 1e-8 * weight * 1e3);
  EXPECT_NEAR(f[2], -weight, 1e-8 * weight * 1e3);
}

// One frictional contact straddling the cut plane at x = 0, and a colliding pair that crosses
// it while in contact: their springs carry on exactly as in the serial run. Soft springs make
// the contacts last about 700 steps.
TEST(Mpi, ContactAcrossAndPairMigratingKeepTheirSprings) {
  auto make = [](Comm comm) {
    auto cfg = test::open_box(4.0, {0, 0, 0}, 1e-4);
    cfg.ranks = {comm.size(), 1, 1};
    cfg.rebalance_every = 0; // keep the cut planes evenly spaced: x = 0 for two ranks
    std::vector<ParticleSpec> specs{
        // meeting across x = 0 while sliding past each other along y
        test::sphere({-0.55, -1.0, 2.0}, 0.5, 1.0, {0.3, 0.3, 0}, {0, 0, 1}),
        test::sphere({0.55, -1.0, 2.0}, 0.5, 1.0, {-0.3, -0.3, 0}),
        // a pair that collides while crossing x = 0
        test::sphere({-1.95, 1.0, -2.0}, 0.5, 1.0, {3.2, 0.1, 0}),
        test::sphere({-0.9, 1.0, -2.0}, 0.5, 1.0, {3.0, -0.1, 0.05})};
    return Simulation(cfg, test::store_of(specs), {}, {},
                      test::linear_law({1e3, 3e2, 0, 0, 0.8, 0.6}), comm);
  };
  Simulation parallel = make(Comm::world());
  parallel.run(5000);
  const Snapshot a = snapshot(parallel);
  if (Comm::world().rank() == 0) {
    Simulation serial = make(Comm::self());
    serial.run(5000);
    ASSERT_GT(serial.energies().dissipated, 0.0); // friction has acted
    expect_same(a, snapshot(serial), 1e-10, 1e-10);
  }
}

// An overlap beyond the limit found on one rank (the grains meet at x = 1.5, on the last rank
// of two or four) stops every rank at the same step with that rank's diagnosis.
TEST(Mpi, AnOverlapBeyondTheLimitStopsEveryRank) {
  const Comm world = Comm::world();
  Simulation sim = test::head_on(1.1, world);
  const std::string diagnosis = test::failure_of(sim, 1000);
  EXPECT_NE(diagnosis.find("overlap of"), std::string::npos) << diagnosis;
  const double step = static_cast<double>(sim.step_count());
  EXPECT_EQ(world.max(step), -world.max(-step)) << "every rank stopped at the same step";
}

// A shallow bed at the bottom of a cubic box: the automatic layout cuts across the bed (x and
// y), not through it, as the least surface over the whole box would (1 x 1 x 2 for two ranks).
TEST(Mpi, LayoutCutsAcrossAShallowBed) {
  const auto cfg = test::open_box(20.0, {0, 0, -1}, 1e-4);
  std::vector<ParticleSpec> bed;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 2; ++k)
        bed.push_back(test::sphere({-19 + 2.0 * i, -19 + 2.0 * j, -19 + 1.0 * k}, 0.45, 1.0));
  const Simulation sim(cfg, test::store_of(bed), {}, {}, test::linear_law({1e3, 0, 0, 0, 0, 0}),
                       Comm::world());
  EXPECT_EQ(sim.decomposition().dims()[2], 1) << sim.decomposition().describe();
}

} // namespace
} // namespace yuxi
