// The distributed engine gives the answers of the serial one (tests/mpi/, run with mpirun -np
// 1, 2 and 4 by ctest): the shaken basin and the thermodynamic model against the
// serial run.
#include "mpi_support.hpp"

#include <gtest/gtest.h>

namespace yuxi {
namespace {

using namespace mpi_test;

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

} // namespace
} // namespace yuxi
