// The distributed engine gives the answers of the serial one: each test runs a system on all
// ranks (MPI_COMM_WORLD) and, on rank 0, the same system on one rank (MPI_COMM_SELF), and
// compares them particle by particle. Run with mpirun -np 1, 2 and 4 (ctest does).
// Round-off differs (forces are summed in another order), so agreement is to a tolerance.
//
// What the tests of the distributed engine share: a snapshot of a run's particles and books,
// its comparison with another's, a dense packing to run, and files that every rank sees.
#pragma once

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

namespace yuxi::mpi_test {

struct Snapshot {
  std::map<GlobalId, std::pair<Vec3, Vec3>> state; // x, v by global id
  EnergyBooks energies;
};

inline Snapshot snapshot(const Simulation& sim) {
  Snapshot s;
  s.energies = sim.energies(); // collective
  const ParticleStore all = sim.gather_particles();
  for (std::size_t i = 0; i < all.n_owned(); ++i) s.state[all.gid[i]] = {all.x[i], all.v[i]};
  return s;
}

// Compares on rank 0: positions to `tol_x` (given `box`, the nearest periodic images: a
// clump's members stand outside the box along an axis cut between ranks), velocities to
// `tol_v`, energies relatively.
inline void expect_same(const Snapshot& a, const Snapshot& b, double tol_x, double tol_v,
                        const Box* box = nullptr) {
  if (Comm::world().rank() != 0) return;
  ASSERT_EQ(a.state.size(), b.state.size()) << "particles are conserved";
  double dx = 0, dv = 0;
  for (const auto& [gid, xv] : a.state) {
    const auto it = b.state.find(gid);
    ASSERT_NE(it, b.state.end()) << "particle " << gid << " lost";
    dx = std::max(dx, norm(box ? box->minimum_image(xv.first, it->second.first)
                               : xv.first - it->second.first));
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
inline Simulation dense(Comm comm, double near_fraction = 0.25, bool rolling = true,
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

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// One folder for all ranks: rank 0's.
inline std::filesystem::path shared_temp_dir(const std::string& name) {
  const Comm comm = Comm::world();
  std::string dir;
  if (comm.root()) dir = test::temp_dir(name).string();
  return comm.broadcast(dir);
}

} // namespace yuxi::mpi_test
