// The fish basin (docs/models/fish-basin.md section 6): the builder reproduces the paper's particle
// counts, the bed settles without losing a grain, and the vibrating wall holds its grains.
#include "io/scene_reader.hpp"
#include "run/scene_builder.hpp"
#include "scene/fish_basin.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

TEST(FishBasin, PaperSizeCountsMatchThePaperWithinFivePercent) {
  const Scene scene = read_scene_file(std::string(YUXI_SCENES_DIR) + "/basin-paper.toml");
  const BuiltParticles b = build_fish_basin(*scene.basin, scene.sim.box.lo);
  // Li & Cai (2008): 56,339 wall particles and 241,550 free grains.
  EXPECT_NEAR(static_cast<double>(b.n_walls), 56339.0, 0.05 * 56339.0);
  EXPECT_NEAR(static_cast<double>(b.n_grains), 241550.0, 0.05 * 241550.0);
}

TEST(FishBasin, PaperSizeSceneRuns) {
  const Scene scene = read_scene_file(std::string(YUXI_SCENES_DIR) + "/basin-paper.toml");
  BuildReport report;
  auto sim = build_simulation(scene, false, &report);
  sim->run(20);
  const auto e = sim->energies();
  EXPECT_EQ(e.grains, report.grains);
  EXPECT_GT(e.translational, 0.0); // falling
  EXPECT_LT(std::abs(e.balance() - sim->energies().balance()), 1e-9);
}

TEST(FishBasin, GrainRadiiFollowTheTruncatedNormalAndMassesAverageOne) {
  FishBasinSpec spec;
  const BuiltParticles b = build_fish_basin(spec);
  const auto& s = b.particles;
  double sum_r = 0, sum_r2 = 0, sum_m = 0, n = 0;
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    if (!s.is_grain(i)) continue;
    EXPECT_GE(s.radius[i], 0.7 - 1e-12);
    EXPECT_LE(s.radius[i], 1.3 + 1e-12);
    EXPECT_NEAR(s.mass[i] / std::pow(s.radius[i], 3),
                s.mass[b.n_walls] / std::pow(s.radius[b.n_walls], 3), 1e-9); // one density
    sum_r += s.radius[i], sum_r2 += s.radius[i] * s.radius[i], sum_m += s.mass[i], ++n;
  }
  const double mean = sum_r / n, sd = std::sqrt(sum_r2 / n - mean * mean);
  EXPECT_NEAR(mean, 1.0, 4 * 0.1 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.1, 0.01);
  EXPECT_NEAR(sum_m / n, 1.0, 1e-12);
}

// A narrow basin (inner radius 4 cells), about 250 grains in 10 lattice layers that settle into
// a bed about two grains deep by t = 14 tau; shaken from t0 = 14.
constexpr double settled = 14.0;
Scene small_basin(double t_end, const char* file = "basin-small.toml") {
  Scene scene = read_scene_file(std::string(YUXI_SCENES_DIR) + "/" + file);
  auto& b = *scene.basin;
  b.cells = {12, 12, 16};
  b.radius = 4.0;
  b.wall_height = 15;
  b.fill_layers = 10;
  b.excitation.t0 = settled;
  scene.sim.box.hi = {36.0, 36.0, 400.0};
  scene.run.t_end = t_end;
  return scene;
}

// Grains below the top of the wall that are beyond the wall particles' inner ring.
int leaked(const Simulation& sim, const FishBasinSpec& b) {
  const auto& s = sim.particles();
  const double cx = 0.5 * b.cells[0] * b.spacing, cy = 0.5 * b.cells[1] * b.spacing;
  const double wall_top = (b.bottom_layers + b.wall_height) * b.spacing;
  int n = 0;
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (s.is_grain(i) && s.x[i].z < wall_top &&
        std::hypot(s.x[i].x - cx, s.x[i].y - cy) > (b.radius + 0.5) * b.spacing)
      ++n;
  return n;
}

TEST(FishBasin, BedSettlesWithoutLosingAGrain) {
  const Scene scene = small_basin(settled);
  auto sim = build_simulation(scene, false);
  const auto start = sim->energies();
  ASSERT_GT(start.grains, 200u);
  sim->run(std::llround(settled / scene.sim.dt));
  const auto end = sim->energies();
  EXPECT_EQ(end.grains, start.grains);
  EXPECT_EQ(end.escaped, 0u);
  EXPECT_EQ(leaked(*sim, *scene.basin), 0);
  // At rest: the kinetic energy left is a tiny fraction of the potential energy released
  // (measured: 6.5e-4), and the grains lean on each other.
  const double released = start.gravitational - end.gravitational;
  ASSERT_GT(released, 0);
  EXPECT_LT(end.kinetic() / released, 2e-3);
  EXPECT_GT(end.contacts, end.grains);
}

TEST(FishBasin, VibratingWallThrowsGrainsUpButNoneThroughIt) {
  const Scene scene = small_basin(settled + 0.5);
  auto sim = build_simulation(scene, false);
  const auto dt = scene.sim.dt;
  sim->run(std::llround(settled / dt));
  const auto before = sim->energies();
  const double height_before = [&] {
    double z = 0;
    for (std::size_t i = 0; i < sim->particles().n_owned(); ++i)
      if (sim->particles().is_grain(i)) z = std::max(z, sim->particles().x[i].z);
    return z;
  }();
  double highest = 0;
  for (int k = 0; k < 10; ++k) {
    sim->run(std::llround(0.05 / dt));
    EXPECT_EQ(leaked(*sim, *scene.basin), 0) << "at t = " << sim->time();
    for (std::size_t i = 0; i < sim->particles().n_owned(); ++i)
      if (sim->particles().is_grain(i)) highest = std::max(highest, sim->particles().x[i].z);
  }
  EXPECT_GT(highest, height_before + 3.0) << "the excitation throws grains up";
  const auto after = sim->energies();
  const double work = after.wall_work - before.wall_work;
  EXPECT_GT(work, 0.0);
  // The books close to within 3 % of the work put in (t_c/dt = 19 here, violent impacts).
  EXPECT_LT(std::abs(after.balance() - before.balance()), 0.03 * work);
}

// The basin with the thermodynamic contact model (scenes/basin-thermo.toml): the bed settles
// and is shaken with the energy books closing, relaxation energy and heat included.
TEST(FishBasin, ThermodynamicModelRunsTheBasinWithItsBooksClosing) {
  const Scene scene = small_basin(settled + 0.3, "basin-thermo.toml");
  ASSERT_EQ(scene.contact_model, "thermodynamic");
  auto sim = build_simulation(scene, false);
  const auto dt = scene.sim.dt;
  const auto start = sim->energies();
  sim->run(std::llround(settled / dt));
  const auto settled_state = sim->energies();
  EXPECT_EQ(settled_state.grains, start.grains);
  EXPECT_EQ(leaked(*sim, *scene.basin), 0);
  // Settling: what gravity released is dissipated, up to the scheme's first-order slip error
  // (measured 0.5 % on basin-thermo at t_c/dt = 46).
  const double released = start.gravitational - settled_state.gravitational;
  EXPECT_GT(settled_state.dissipated, 0.9 * released);
  EXPECT_LT(std::abs(settled_state.balance() - start.balance()), 0.01 * settled_state.dissipated);
  sim->run(std::llround(0.3 / dt));
  const auto shaken = sim->energies();
  const double work = shaken.wall_work - settled_state.wall_work;
  EXPECT_GT(work, 0.0);
  EXPECT_GT(shaken.relaxation, 0.0); // impacts fill the relaxation buffers
  EXPECT_EQ(leaked(*sim, *scene.basin), 0);
  EXPECT_LT(std::abs(shaken.balance() - settled_state.balance()), 0.01 * work);
}

} // namespace
} // namespace yuxi
