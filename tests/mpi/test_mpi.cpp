// The distributed engine gives the answers of the serial one: each test runs a system on all
// ranks (MPI_COMM_WORLD) and, on rank 0, the same system on one rank (MPI_COMM_SELF), and
// compares them particle by particle. Run with mpirun -np 1, 2 and 4 (ctest does).
// Round-off differs (forces are summed in another order), so agreement is to a tolerance.
#include "core/archive.hpp"
#include "core/random.hpp"
#include "core/units.hpp"
#include "domain/mpi_session.hpp"
#include "domain/shared_file.hpp"
#include "io/lammps_dump_writer.hpp"
#include "io/scene_reader.hpp"
#include "io/vtk_writer.hpp"
#include "run/particle_elastic_energy.hpp"
#include "run/scene_builder.hpp"
#include "run/simulation_checkpoint.hpp"
#include "scene/closest_point_on_triangle.hpp"
#include "temp_folder.hpp"
#include "test_support.hpp"

#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <mpi.h>
#include <set>
#include <sstream>

namespace yuxi {
namespace {

struct Snapshot {
  std::map<GlobalId, std::pair<Vec3, Vec3>> state; // x, v by global id
  EnergyBooks energies;
};

Snapshot snapshot(const Simulation& sim) {
  Snapshot s;
  s.energies = sim.energies(); // collective
  const ParticleStore all = sim.gather_particles();
  for (std::size_t i = 0; i < all.n_owned(); ++i) s.state[all.gid[i]] = {all.x[i], all.v[i]};
  return s;
}

// Compares on rank 0: positions to `tol_x`, velocities to `tol_v`, energies relatively.
void expect_same(const Snapshot& a, const Snapshot& b, double tol_x, double tol_v) {
  if (Comm::world().rank() != 0) return;
  ASSERT_EQ(a.state.size(), b.state.size()) << "particles are conserved";
  double dx = 0, dv = 0;
  for (const auto& [gid, xv] : a.state) {
    const auto it = b.state.find(gid);
    ASSERT_NE(it, b.state.end()) << "particle " << gid << " lost";
    dx = std::max(dx, norm(xv.first - it->second.first));
    dv = std::max(dv, norm(xv.second - it->second.second));
  }
  EXPECT_LE(dx, tol_x);
  EXPECT_LE(dv, tol_v);
  const auto& e = a.energies;
  const auto& f = b.energies;
  EXPECT_EQ(e.grains, f.grains);
  EXPECT_NEAR(e.kinetic(), f.kinetic(), 1e-8 * std::max(1.0, e.kinetic()));
  EXPECT_NEAR(e.elastic, f.elastic, 1e-6 * std::max(1.0, e.elastic));
  EXPECT_NEAR(e.dissipated, f.dissipated, 1e-8 * std::max(1.0, e.dissipated));
  EXPECT_NEAR(e.balance(), f.balance(), 1e-8 * std::max(1.0, std::abs(e.balance())));
}

// A dense, frictional, polydisperse packing, periodic in x and y, walls below and above.
// `near_fraction`, `balance_by`: SimulationConfig's (by time: at every list build); without
// rolling resistance the law runs in SIMD batches.
Simulation dense(Comm comm, double near_fraction = 0.25, bool rolling = true,
                 BalanceBy balance_by = BalanceBy::pairs) {
  Random rng(17);
  auto cfg = test::open_box(6.0, {0.2, 0.1, -1.0}, 2e-4);
  cfg.box.boundary = {Boundary::periodic, Boundary::periodic, Boundary::wall};
  cfg.skin = 0.15;
  cfg.near_fraction = near_fraction;
  cfg.balance_by = balance_by;
  if (balance_by == BalanceBy::time) cfg.rebalance_every = 1;
  std::vector<ParticleSpec> specs;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      for (int k = 0; k < 10; ++k) {
        const double r = rng.uniform(0.4, 0.5);
        specs.push_back(test::sphere({-5.5 + 0.92 * i, -5.5 + 0.92 * j, -5.5 + 0.92 * k}, r,
                                     r * r * r,
                                     {rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)},
                                     {rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)}));
      }
  test::Coeffs c{2e4, 6e3, 20.0, 10.0, 0.5, 0.3};
  if (rolling) {
    c.k_r = 2e3;
    c.mu_r = 0.05;
  }
  return Simulation(cfg, test::store_of(specs), {}, {}, test::linear_law(c), comm);
}

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
    for (double x : sim.contact_record().plane_elastic) sum[1] += 0.5 * x;
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

// The basin: wall particles with prescribed motion across ranks, balanced cuts.
Scene small_basin() {
  Scene scene = read_scene_file(std::string(YUXI_SCENES_DIR) + "/basin-small.toml");
  auto& b = *scene.basin;
  b.cells = {14, 14, 10};
  b.radius = 5.0;
  b.wall_height = 9;
  b.fill_layers = 3;
  b.excitation.t0 = 0.2;
  b.wall_radius = 1.5; // no empty cells along the wall: the shaking reaches the grains at once
  scene.sim.box.hi = {42.0, 42.0, 300.0};
  return scene; // ranks = [0, 0, 1] from basin-small: cut in x and y
}

// The shaken basin is chaotic: the round-off of a different summation order (first seen at step
// 2500, 1e-15) grows about tenfold every 250 steps (measured: 3e-11 at step 4000, 1e-2 at 8000),
// so the runs are compared at step 4000, 2000 steps into the shaking.
TEST(Mpi, ShakenBasinMatchesTheSerialRun) {
  const Scene scene = small_basin();
  auto parallel = build_simulation(scene, false);
  parallel->run(4000); // to t = 0.4: grains falling onto the shaking wall
  const double imbalance = parallel->imbalance(); // collective
  if (Comm::world().size() == 2) {
    EXPECT_LT(imbalance, 1.1);
  }
  const Snapshot a = snapshot(*parallel);
  // The serial reference: the same scene built on one rank.
  if (Comm::world().rank() == 0) {
    BuildReport r;
    auto serial = build_simulation(scene, false, &r, Comm::self());
    serial->run(4000);
    ASSERT_GT(serial->energies().wall_work, 0.0);
    expect_same(a, snapshot(*serial), 1e-8, 1e-6);
  }
}

// The thermodynamic model across ranks: its per-contact state (spring deformations, relaxation
// energy, previous normal) migrates and is mirrored like any history, and the books with their
// relaxation column agree with the serial run.
TEST(Mpi, ThermodynamicModelMatchesTheSerialRun) {
  const auto make = [](Comm comm) {
    Random rng(23);
    auto cfg = test::open_box(6.0, {0.2, 0.1, -1.0}, 1e-4);
    cfg.box.boundary = {Boundary::periodic, Boundary::periodic, Boundary::wall};
    cfg.skin = 0.15;
    std::vector<ParticleSpec> specs;
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j)
        for (int k = 0; k < 8; ++k) {
          const double r = rng.uniform(0.4, 0.5);
          specs.push_back(
              test::sphere({-5.5 + 0.92 * i, -5.5 + 0.92 * j, -5.5 + 0.92 * k}, r, r * r * r,
                           {rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)},
                           {rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5)}));
        }
    Thermodynamic::Coeffs c; // REF, E* such that k = 2e4 at R* = 0.225
    c.e_star = 2e4 / (4.0 / 3.0 * std::sqrt(0.225));
    ContactLaw<Thermodynamic> law{PairTable<Thermodynamic::Coeffs>(1)};
    law.coeffs.set(0, 0, c);
    return Simulation(cfg, test::store_of(specs), {}, {}, law, comm);
  };
  Simulation parallel = make(Comm::world());
  parallel.run(400);
  const Snapshot a = snapshot(parallel);
  const double relaxation = parallel.energies().relaxation; // collective
  if (Comm::world().rank() == 0) {
    Simulation serial = make(Comm::self());
    serial.run(400);
    EXPECT_GT(serial.energies().contacts, 150u);
    EXPECT_GT(serial.energies().relaxation, 0.0);
    EXPECT_NEAR(relaxation, serial.energies().relaxation, 1e-8 * serial.energies().relaxation);
    expect_same(a, snapshot(serial), 1e-9, 1e-7);
  }
}

// A rotating drum of radius 5 about the y axis (a mesh of 48 facets with caps, or an analytic
// capped cylinder) half full of grains: wall contacts live with their grains across ranks, move
// with them, and the run agrees with the serial one (1000 steps; grains tumble against the
// turning wall, so the tolerances are those of the other chaotic runs here: 6000 steps,
// positions to 1e-9, velocities to 1e-7, the wall's work and the books to 1e-8 and 1e-10).
Simulation rotating_drum(bool meshed, Comm comm, double omega = 0.5) {
  SimulationConfig cfg;
  cfg.box = {{-6, -0.5, -6}, {6, 3.5, 6}};
  cfg.gravity = {0, 0, -9.81};
  cfg.dt = 1e-4;
  cfg.skin = 0.1;
  cfg.ranks = {comm.size(), 1, 1};
  const double R = 5, L = 3;
  std::vector<ParticleSpec> grains;
  Random rng(5);
  for (double x = -4.2; x <= 4.2; x += 0.79)
    for (double y = 0.45; y <= L - 0.45; y += 0.79)
      for (double z = -4.5; z <= 0.0; z += 0.79)
        if (std::hypot(x, z) < R - 0.6)
          grains.push_back(test::sphere({x, y, z}, rng.uniform(0.37, 0.395), 0.3,
                                        {rng.uniform(-1, 1), rng.uniform(-1, 1), 0}));
  std::vector<ShapedWall> walls;
  if (meshed) {
    std::vector<std::array<Vec3, 3>> soup;
    const int n = 48;
    for (int k = 0; k < n; ++k) {
      const double a0 = 2 * pi * k / n, a1 = 2 * pi * (k + 1) / n;
      const Vec3 a{R * std::cos(a0), 0, R * std::sin(a0)}, b{R * std::cos(a1), 0, R * std::sin(a1)};
      const Vec3 c = b + Vec3{0, L, 0}, d = a + Vec3{0, L, 0};
      soup.push_back({a, b, c});
      soup.push_back({a, c, d});
      soup.push_back({Vec3{}, b, a});
      soup.push_back({Vec3{0, L, 0}, d, c});
    }
    MeshWall m;
    m.name = "drum";
    m.mesh = TriangleMesh::weld(soup);
    RigidMotion turn;
    turn.axis = {0, 1, 0};
    turn.omega = omega;
    if (omega != 0.0) m.motion = turn;
    walls.push_back(m);
  } else {
    CylinderWall c;
    c.name = "drum";
    c.axis = {0, 1, 0};
    c.radius = R;
    c.lo = 0, c.hi = L, c.capped = true;
    c.omega = omega;
    walls.push_back(c);
  }
  return Simulation(cfg, test::store_of(grains), {}, {},
                    test::linear_law({2e4, 2e4 * 2 / 7, 20, 10, 0.5, 0.4}), comm, walls);
}

// Of the drum's mesh, each rank holds only the triangles near its grains: fewer than the whole
// (the bed lies in the drum's lower half), and every triangle that comes within a grain's
// radius plus the skin of one of its grains.
void expect_held_in_parts(const Simulation& sim, const Comm& world, std::size_t wall = 0) {
  const auto& mesh = std::get<MeshWall>(sim.walls()[wall]);
  const TriangleMesh& whole = mesh.whole_mesh();
  EXPECT_LT(mesh.mesh.n_triangles(), whole.n_triangles()) << "rank " << world.rank();
  std::vector<char> held(whole.n_triangles(), 0);
  for (std::uint32_t t = 0; t < mesh.mesh.n_triangles(); ++t) held[mesh.element_of(t)] = 1;
  const std::vector<Vec3> at = mesh.placed_whole();
  const ParticleStore& p = sim.particles();
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    if (!p.is_grain(i)) continue;
    for (std::size_t t = 0; t < whole.n_triangles(); ++t) {
      const auto& tri = whole.triangles[t];
      const Vec3 q = closest_point_on_triangle(p.x[i], at[tri[0]], at[tri[1]], at[tri[2]]).point;
      if (norm(p.x[i] - q) < p.radius[i] + 0.1) { // (the drum's skin)
        EXPECT_TRUE(held[t]) << "rank " << world.rank() << ", triangle " << t;
      }
    }
  }
}

// The force on every triangle agrees with the serial run's (`expected`, on rank 0), and the bed
// presses on `loaded_at_least` of them or more.
void expect_same_triangle_forces(const std::vector<Vec3>& forces, const std::vector<Vec3>& expected,
                                 int loaded_at_least = 4) {
  ASSERT_EQ(forces.size(), expected.size());
  double loaded = 0;
  for (std::size_t t = 0; t < forces.size(); ++t) {
    EXPECT_LT(norm(forces[t] - expected[t]), 1e-7 * (1 + norm(expected[t]))) << "triangle " << t;
    loaded += norm(expected[t]) > 0 ? 1 : 0;
  }
  EXPECT_GE(loaded, loaded_at_least);
}

// The turning drum: a meshed one is held in parts too, chosen again where it stands at every
// list build, and its run agrees with the serial one.
TEST(Mpi, RotatingDrumMatchesTheSerialRun) {
  const Comm world = Comm::world();
  for (const bool meshed : {true, false}) {
    Simulation parallel = rotating_drum(meshed, world);
    parallel.run(6000);
    const Snapshot a = snapshot(parallel);
    const double work = parallel.wall_loads()[0].work; // collective
    std::vector<Vec3> forces;
    if (meshed) {
      expect_held_in_parts(parallel, world);
      forces = parallel.triangle_forces(0); // collective
    }
    if (world.rank() == 0) {
      Simulation serial = rotating_drum(meshed, Comm::self());
      serial.run(6000);
      const Snapshot b = snapshot(serial);
      EXPECT_GT(b.energies.contacts, 30u); // the bed has reached the wall
      EXPECT_NE(serial.wall_loads()[0].work, 0.0);
      EXPECT_NEAR(work, serial.wall_loads()[0].work, 1e-8 * std::abs(serial.wall_loads()[0].work))
          << (meshed ? "mesh" : "cylinder");
      EXPECT_NEAR(a.energies.balance(), b.energies.balance(),
                  1e-10 * std::abs(b.energies.balance()));
      expect_same(a, b, 1e-9, 1e-7);
      if (meshed) expect_same_triangle_forces(forces, serial.triangle_forces(0));
    }
  }
}

// The drum's mesh standing still, the bed settling in it: held in parts, and the run, its wall
// force on each triangle included, agrees with the serial one (the tolerances of the turning
// drum above).
TEST(Mpi, AStillMeshIsHeldInPartsAndTheRunMatchesTheSerialOne) {
  const Comm world = Comm::world();
  Simulation parallel = rotating_drum(true, world, 0.0);
  parallel.run(4000);
  const Snapshot a = snapshot(parallel);
  expect_held_in_parts(parallel, world);
  const std::vector<Vec3> forces = parallel.triangle_forces(0); // collective
  if (world.rank() == 0) {
    Simulation serial = rotating_drum(true, Comm::self(), 0.0);
    serial.run(4000);
    expect_same_triangle_forces(forces, serial.triangle_forces(0));
    EXPECT_NEAR(a.energies.balance(), snapshot(serial).energies.balance(),
                1e-10 * std::abs(snapshot(serial).energies.balance()));
    expect_same(a, snapshot(serial), 1e-9, 1e-7);
  }
}

// A bin on a floor: 188 grains at rest on a lattice; the bin's side a vertical cylinder mesh of
// radius 3.6 (64 facets round, 6 rings high) that deforms in the basin's radial mode from
// t = 0.1 (m = 2, dr = 0.5, omega = 5), and over the grains a servo lid (a 12 x 12 grid of
// squares, 288 triangles, at z = 4.3) that comes down at up to 5 until they push back with 400,
// about half their weight. Neither mesh moves rigidly: the part of it that a rank holds is
// chosen again at every list build, and between builds a bound on how far any point of the mesh
// can have moved says when the next one is due (MeshWall::moved2_since_build).
Simulation bin_under_servo_lid(Comm comm) {
  SimulationConfig cfg;
  cfg.box = {{-5, -5, -0.5}, {5, 5, 6}};
  cfg.gravity = {0, 0, -9.81};
  cfg.dt = 1e-4;
  cfg.skin = 0.1;
  cfg.ranks = {comm.size(), 1, 1};
  std::vector<ParticleSpec> grains;
  Random rng(11);
  for (double x = -3.2; x <= 3.2; x += 0.79)
    for (double y = -3.2; y <= 3.2; y += 0.79)
      for (double z = 0.45; z <= 2.9; z += 0.79)
        if (std::hypot(x, y) < 3.2)
          grains.push_back(test::sphere({x, y, z}, rng.uniform(0.37, 0.395), 0.3));
  const double R = 3.6, H = 5;
  const int round = 64, rings = 6;
  std::vector<std::array<Vec3, 3>> side;
  for (int k = 0; k < round; ++k)
    for (int j = 0; j < rings; ++j) {
      const double a0 = 2 * pi * k / round, a1 = 2 * pi * (k + 1) / round;
      const double z0 = H * j / rings, z1 = H * (j + 1) / rings;
      const Vec3 a{R * std::cos(a0), R * std::sin(a0), z0},
          b{R * std::cos(a1), R * std::sin(a1), z0};
      const Vec3 c{b.x, b.y, z1}, d{a.x, a.y, z1};
      side.push_back({a, b, c});
      side.push_back({a, c, d});
    }
  MeshWall wall;
  wall.name = "side";
  wall.mesh = TriangleMesh::weld(side);
  RadialCosineMotion mode;
  mode.mode = 2, mode.amplitude = 0.5, mode.omega = 5, mode.t0 = 0.1;
  wall.motion = mode;
  std::vector<std::array<Vec3, 3>> grid;
  const int n = 12;
  const double h = 9.0 / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 a{-4.5 + h * i, -4.5 + h * j, 4.3}, b = a + Vec3{h, 0, 0}, c = a + Vec3{h, h, 0},
                                                     d = a + Vec3{0, h, 0};
      grid.push_back({a, b, c});
      grid.push_back({a, c, d});
    }
  MeshWall lid;
  lid.name = "lid";
  lid.mesh = TriangleMesh::weld(grid);
  lid.controller = std::make_shared<ForceServo>(400.0, 0.02, 5.0);
  return Simulation(cfg, test::store_of(grains), {test::plane({0, 0, 0}, {0, 0, 1})}, {},
                    test::linear_law({2e4, 2e4 * 2 / 7, 20, 10, 0.5, 0.4}), comm, {wall, lid});
}

// The bin's deforming side and its servo lid are held in parts; the run agrees with the serial
// one after 3000 steps (the tolerances of the turning drum: the servo, whose speed follows the
// force summed over the ranks, couples every grain under the lid, and round-off grows past them
// by 6000). On these ranks a checkpoint written while the lid comes down at full speed (at step
// 651; the lid, not the grains at rest, calls for every list build then) resumes bit for bit to
// step 6000: the list built again at loading is the saved run's, the lid standing where it stood at
// that build. (Built with the lid where it stands at the checkpoint instead, the resumed run
// differs from the straight one.)
TEST(Mpi, DeformingAndServoMeshesAreHeldInPartsAndResumeBitForBit) {
  const Comm world = Comm::world();
  Simulation parallel = bin_under_servo_lid(world);
  parallel.run(651);
  ArchiveWriter saved;
  parallel.checkpoint(saved);
  parallel.run(2349);
  const Snapshot a = snapshot(parallel);
  if (world.size() > 1)
    for (std::size_t w : {0u, 1u}) expect_held_in_parts(parallel, world, w);
  const auto& lid = std::get<MeshWall>(parallel.walls()[1]);
  EXPECT_GT(lid.servo_offset, 0.2) << "the lid came down"; // (along its axis, -z)
  const double work = parallel.wall_loads()[0].work;       // collective
  const std::vector<Vec3> side_forces = parallel.triangle_forces(0),
                          lid_forces = parallel.triangle_forces(1);
  parallel.run(3000); // (on, for the resume: the lid presses on)
  ArchiveWriter straight;
  parallel.checkpoint(straight);

  Simulation resumed = bin_under_servo_lid(world);
  ArchiveReader reader(saved.data());
  resumed.checkpoint(reader);
  resumed.run(5349);
  ArchiveWriter after;
  resumed.checkpoint(after);
  EXPECT_TRUE(straight.data() == after.data()) << "rank " << world.rank();

  if (world.rank() == 0) {
    Simulation serial = bin_under_servo_lid(Comm::self());
    serial.run(3000);
    EXPECT_GE(serial.wall_loads()[1].contacts, 4u); // the lid presses on the bed
    EXPECT_NE(serial.wall_loads()[0].work, 0.0);
    EXPECT_NEAR(work, serial.wall_loads()[0].work, 1e-8 * std::abs(serial.wall_loads()[0].work));
    expect_same(a, snapshot(serial), 1e-9, 1e-7);
    expect_same_triangle_forces(side_forces, serial.triangle_forces(0), 1); // (grains it hit
    expect_same_triangle_forces(lid_forces, serial.triangle_forces(1));     // fly off again)
  }
}

// A message of `bytes` from rank `from`, different at every byte and for every sender.
std::string message_of(int from, std::size_t bytes) {
  std::string m(bytes, '\0');
  for (std::size_t k = 0; k < bytes; ++k) m[k] = static_cast<char>((k * 131 + 7 * from) % 251);
  return m;
}

// A started exchange travels in pieces (comm.hpp), blocking ones in one message: messages of
// no byte, of one piece, of many, and of more than max_exchange_pieces arrive whole either way.
TEST(Mpi, ExchangesInPiecesArriveWhole) {
  const Comm comm = Comm::world();
  const int to = (comm.rank() + 1) % comm.size();
  const int from = (comm.rank() + comm.size() - 1) % comm.size();
  const std::size_t sizes[] = {0,
                               1,
                               Comm::exchange_piece_bytes - 1,
                               Comm::exchange_piece_bytes,
                               Comm::exchange_piece_bytes + 1,
                               100000,
                               Comm::exchange_piece_bytes * Comm::max_exchange_pieces * 3 + 5};
  int tag = 900;
  for (const std::size_t bytes : sizes) {
    for (const bool started : {false, true}) {
      const std::string out = message_of(comm.rank(), bytes);
      std::string in = "stale";
      if (started) {
        Comm::Exchange e = comm.start_send_receive(to, out, from, in, bytes, tag);
        comm.wait_receive(e);
        comm.wait_send(e);
      } else {
        comm.send_receive(to, out, from, in, bytes, tag);
      }
      EXPECT_EQ(in, message_of(from, bytes)) << bytes << " bytes";
      tag += 2;
    }
  }
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// One folder for all ranks: rank 0's.
std::filesystem::path shared_temp_dir(const std::string& name) {
  const Comm comm = Comm::world();
  std::string dir;
  if (comm.root()) dir = test::temp_dir(name).string();
  return comm.broadcast(dir);
}

TEST(Mpi, SharedFileHoldsEveryRanksBytesInRankOrder) {
  const Comm comm = Comm::world();
  const auto dir = shared_temp_dir("shared_file");
  const auto path = dir / "f.bin";
  const std::string mine =
      message_of(comm.rank(), 1000 + 3000 * static_cast<std::size_t>(comm.rank()));
  std::uint64_t end = 0;
  {
    SharedFile f(comm, path, SharedFile::Mode::truncate);
    EXPECT_EQ(f.size_at_open(), 0u);
    if (comm.root()) f.write_at(0, "head");
    end = f.write_in_rank_order(4, mine);
    f.close(true);
  }
  { // appended after what the file holds
    SharedFile f(comm, path, SharedFile::Mode::append);
    EXPECT_EQ(f.size_at_open(), end);
    f.write_in_rank_order(f.size_at_open(), mine);
    f.close(false);
  }
  if (comm.root()) {
    std::string expected;
    for (int r = 0; r < comm.size(); ++r)
      expected += message_of(r, 1000 + 3000 * static_cast<std::size_t>(r));
    EXPECT_EQ(end, 4 + expected.size());
    EXPECT_EQ(slurp(path), "head" + expected + expected);
    std::filesystem::remove_all(dir);
  }
}

TEST(Mpi, SharedFileReportsAFailureOnEveryRank) {
  const Comm comm = Comm::world();
  const auto dir = shared_temp_dir("shared_file_missing");
  const auto path = dir / "no_such_folder" / "f.bin";
  bool thrown = false;
  try {
    SharedFile f(comm, path, SharedFile::Mode::truncate);
    f.write_in_rank_order(0, "x");
    f.close(false);
  } catch (const std::runtime_error& e) {
    thrown = true;
    EXPECT_NE(std::string(e.what()).find("no_such_folder"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(thrown);
  if (comm.root()) std::filesystem::remove_all(dir);
}

// A checkpoint that every rank wrote is read back in shares: each rank reads and holds its own
// section alone, loads it into a new simulation to the same state, and a damaged byte in any
// rank's section is refused on every rank (the file's CRC, combined from the ranks' parts).
TEST(Mpi, CheckpointIsReadBackInSharesAndVerifiedWhole) {
  const Comm comm = Comm::world();
  Simulation sim = dense(comm);
  sim.run(31); // (a checkpoint may follow any step)
  const auto dir = shared_temp_dir("checkpoint_shares");
  const auto path = dir / "c.yxc";
  write_checkpoint(path, "scene text", sim);
  ArchiveWriter mine;
  sim.checkpoint(mine);

  const CheckpointData d = read_checkpoint(path, comm);
  EXPECT_EQ(d.scene_text, "scene text");
  EXPECT_EQ(d.step, 31);
  EXPECT_EQ(d.n_sections, static_cast<std::uint64_t>(comm.size()));
  EXPECT_EQ(d.first_section, static_cast<std::uint64_t>(comm.rank()));
  ASSERT_EQ(d.sections.size(), 1u);
  EXPECT_TRUE(d.sections[0] == mine.data()) << "this rank's own section";
  Simulation loaded = dense(comm); // continues as the original, bit for bit
  apply_checkpoint(d, loaded);
  sim.run(20);
  loaded.run(20);
  expect_same(snapshot(sim), snapshot(loaded), 0.0, 0.0);

  if (comm.root()) { // a group of one reads every section
    const CheckpointData all = read_checkpoint(path, Comm::self());
    EXPECT_EQ(all.sections.size(), static_cast<std::size_t>(comm.size()));
    EXPECT_TRUE(all.sections[0] == mine.data());
  }
  comm.barrier();
  if (comm.rank() == comm.size() - 1) { // a byte of the last rank's section
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(std::filesystem::file_size(path) - 4 - 100));
    f.put('\x5a');
  }
  comm.barrier();
  bool refused = false;
  try {
    read_checkpoint(path, comm);
  } catch (const CheckpointError& e) {
    refused = true;
    EXPECT_NE(std::string(e.what()).find("c.yxc: checksum mismatch"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(refused);
  comm.barrier();
  if (comm.root()) std::filesystem::remove_all(dir);
}

// A run resumed on as many ranks keeps the saved cut planes, even where the saved run was due
// to move them at its next list build (here the first, rebuilds() == 1): the loaded run
// balances at that build too, not while loading, with no list to weigh the particles by.
TEST(Mpi, ALoadedRunKeepsItsCutPlanesUntilItsNextBalancing) {
  const Comm comm = Comm::world();
  Simulation sim = dense(comm);
  ASSERT_EQ(sim.rebuilds(), 1);
  const auto dir = shared_temp_dir("checkpoint_cuts");
  write_checkpoint(dir / "c.yxc", "", sim);
  Simulation loaded = dense(comm);
  apply_checkpoint(read_checkpoint(dir / "c.yxc", comm), loaded);
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(loaded.decomposition().cuts(a), sim.decomposition().cuts(a)) << "axis " << a;
  sim.request_rebuild();
  loaded.request_rebuild();
  sim.step();
  loaded.step();
  for (int a = 0; a < 3; ++a)
    EXPECT_EQ(loaded.decomposition().cuts(a), sim.decomposition().cuts(a)) << "axis " << a;
  comm.barrier();
  if (comm.root()) std::filesystem::remove_all(dir);
}

// Every rank writes its own particles into the one VTK file and the one LAMMPS dump frame; each
// particle is in them once, with its values, whatever the number of ranks.
TEST(Mpi, SnapshotsHoldEveryParticleOnceFromEveryRank) {
  const Comm comm = Comm::world();
  Simulation sim = dense(comm);
  sim.run(50);
  const auto dir = shared_temp_dir("snapshots");
  write_vtu(dir / "p.vtu", sim.particles(), comm);
  const Box box{{-6, -6, -6}, {6, 6, 6}, {Boundary::periodic, Boundary::periodic, Boundary::wall}};
  {
    LammpsDumpWriter dump(dir / "p.lammpstrj", box, std::nullopt, comm);
    dump.write(sim.particles(), 50);
  }
  const ParticleStore all = sim.gather_particles();
  if (!comm.root()) return;
  std::map<GlobalId, std::size_t> index; // gathered particle of each id
  for (std::size_t i = 0; i < all.n_owned(); ++i) index[all.gid[i]] = i;
  ASSERT_EQ(index.size(), 1440u);

  // The dump: its header counts them all, and each line is one particle, once.
  std::istringstream dump(slurp(dir / "p.lammpstrj"));
  std::vector<std::string> lines;
  for (std::string l; std::getline(dump, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 9 + index.size());
  EXPECT_EQ(lines[3], "1440");
  std::set<GlobalId> seen;
  for (std::size_t k = 9; k < lines.size(); ++k) {
    std::istringstream row(lines[k]);
    GlobalId id = 0;
    int type = 0;
    double radius = 0, mass = 0, x = 0;
    row >> id >> type >> radius >> mass >> x;
    ASSERT_TRUE(index.count(id)) << lines[k];
    EXPECT_TRUE(seen.insert(id).second) << "particle " << id << " twice";
    EXPECT_NEAR(radius, all.radius[index[id]], 1e-7); // (8 significant digits)
    EXPECT_NEAR(x, all.x[index[id]].x, 1e-8);
  }

  // The VTK file: the ids and points arrays hold every particle once, ids with their points.
  const std::string vtu = slurp(dir / "p.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"1440\""), std::string::npos);
  const std::size_t data = vtu.find('_', vtu.find("<AppendedData")) + 1;
  const auto array_at = [&](const std::string& name) {
    const std::size_t decl = vtu.find("Name=\"" + name + "\"");
    const std::size_t off = vtu.find("offset=\"", decl) + 8;
    const std::size_t at = data + std::stoull(vtu.substr(off, vtu.find('"', off) - off));
    std::uint64_t size = 0;
    std::memcpy(&size, vtu.data() + at, sizeof size);
    return std::make_pair(at + sizeof size, size);
  };
  const auto [ids, id_bytes] = array_at("id");
  const auto [points, point_bytes] = array_at("Points");
  ASSERT_EQ(id_bytes, 1440u * 8);
  ASSERT_EQ(point_bytes, 1440u * 24);
  seen.clear();
  for (std::size_t k = 0; k < 1440; ++k) {
    std::int64_t id = 0;
    double p[3];
    std::memcpy(&id, vtu.data() + ids + 8 * k, 8);
    std::memcpy(p, vtu.data() + points + 24 * k, 24);
    ASSERT_TRUE(index.count(id)) << "id " << id;
    EXPECT_TRUE(seen.insert(id).second) << "particle " << id << " twice";
    const Vec3& x = all.x[index[id]];
    EXPECT_EQ(p[0], x.x);
    EXPECT_EQ(p[1], x.y);
    EXPECT_EQ(p[2], x.z);
  }
  // The last cell's offset is the number of points: the ranks' cells follow each other.
  const auto [offsets, offset_bytes] = array_at("offsets");
  std::int64_t last = 0;
  std::memcpy(&last, vtu.data() + offsets + offset_bytes - 8, 8);
  EXPECT_EQ(last, 1440);
  EXPECT_NE(vtu.rfind("</VTKFile>"), std::string::npos);
  std::filesystem::remove_all(dir);
}

} // namespace
} // namespace yuxi

int main(int argc, char** argv) {
  const yuxi::MpiSession mpi(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank != 0) { // one report
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int failed = RUN_ALL_TESTS();
  int any = failed;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return any;
}
