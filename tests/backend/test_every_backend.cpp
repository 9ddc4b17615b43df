// One test, every backend: each case runs on every backend this build has and is compared with
// the CPU reference (Backend::cpu_reference, every contact one by one through its law), the
// oracle, to the tolerance the case states (the pattern of OpenMM's reference platform). The
// backends today are the CPU engine's (`cpu`: the linear law in SIMD lanes, for pairs and for
// mesh and cylinder contacts); a device backend joins backends() and every case runs on it.
// The cases cover each contact law, wall particles in motion, meshes, cylinders, inserts and
// outlets.
#include "io/scene_reader.hpp"
#include "run/scene_builder.hpp"
#include "small_basin.hpp"

#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <ostream>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

namespace yuxi {
namespace {

struct BackendCase {
  const char* name;
  const char* scene; // under scenes/
  double t_end;      // run from t = 0 to here
  // A basin of scenes/basin-models/ shrunk to a case of seconds (small_basin()).
  bool small_basin;
  // The largest difference allowed from the oracle, relative to the largest magnitude of each
  // quantity (positions, velocities, angular velocities; the energy books' balance and
  // dissipation), per backend: 0 for the CPU's own paths, which must agree to the bit.
  double cpu_tolerance;
};

void PrintTo(const BackendCase& c, std::ostream* os) {
  *os << c.name;
}

struct NamedBackend {
  const char* name;
  Backend backend;
  double BackendCase::*tolerance;
};

// Every backend of this build but the oracle.
std::vector<NamedBackend> backends() {
  return {{"cpu", Backend::cpu, &BackendCase::cpu_tolerance}};
}

std::unique_ptr<Simulation> run_case(const BackendCase& c, Backend backend) {
  const std::string path = std::string(YUXI_SCENES_DIR "/") + c.scene;
  std::ifstream in(path);
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  Scene scene = read_scene_text(c.small_basin ? test::small_basin(text) : text, path);
  scene.sim.backend = backend;
  auto sim = build_simulation(scene, false);
  sim->run(std::llround(c.t_end / scene.sim.dt));
  return sim;
}

// max |a - b| over max |a| (0 where both are zero everywhere).
template <class Get> double relative_difference(std::size_t n, Get&& get) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto [a, b] = get(i);
    for (int k = 0; k < 3; ++k) {
      diff = std::max(diff, std::abs(a[k] - b[k]));
      scale = std::max(scale, std::abs(a[k]));
    }
  }
  return scale > 0.0 ? diff / scale : diff;
}

class EveryBackend : public testing::TestWithParam<BackendCase> {};

TEST_P(EveryBackend, AgreesWithTheCpuReference) {
  const BackendCase& c = GetParam();
  const auto oracle = run_case(c, Backend::cpu_reference);
  const ParticleStore expected = oracle->gather_particles();
  const EnergyBooks expected_books = oracle->energies();
  ASSERT_GT(oracle->last_tally().touching, 0u) << "the case must have contacts";
  ASSERT_GT(expected_books.dissipated, 0.0) << "the case must dissipate in contacts";
  for (const NamedBackend& b : backends()) {
    SCOPED_TRACE(b.name);
    const double tolerance = c.*(b.tolerance);
    const auto sim = run_case(c, b.backend);
    const ParticleStore got = sim->gather_particles();
    ASSERT_EQ(got.n_owned(), expected.n_owned());
    for (std::size_t i = 0; i < got.n_owned(); ++i) ASSERT_EQ(got.gid[i], expected.gid[i]);
    const std::size_t n = got.n_owned();
    const auto of = [&](const std::vector<Vec3>& a, const std::vector<Vec3>& e) {
      return relative_difference(n, [&](std::size_t i) { return std::pair{a[i], e[i]}; });
    };
    EXPECT_LE(of(got.x, expected.x), tolerance) << "positions";
    EXPECT_LE(of(got.v, expected.v), tolerance) << "velocities";
    EXPECT_LE(of(got.w, expected.w), tolerance) << "angular velocities";
    const EnergyBooks books = sim->energies();
    const double scale = std::max(std::abs(expected_books.mechanical()), 1e-300);
    EXPECT_LE(std::abs(books.balance() - expected_books.balance()) / scale, tolerance);
    EXPECT_LE(std::abs(books.dissipated - expected_books.dissipated) / scale, tolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, EveryBackend,
    testing::Values(
        BackendCase{"basin_linear_wall_particles", "basin-models/basin-small-linear.toml", 3.5,
                    true, 0.0},
        BackendCase{"basin_hertz_mindlin", "basin-models/basin-small-hertz.toml", 3.5, true, 0.0},
        BackendCase{"basin_luding", "basin-models/basin-small-luding.toml", 3.5, true, 0.0},
        BackendCase{"basin_thermodynamic", "basin-models/basin-small-thermo.toml", 3.5, true, 0.0},
        BackendCase{"drum_mesh", "bulk/drum-small.toml", 1.2, false, 0.0},
        BackendCase{"drum_cylinder", "drum/drum-cylinder.toml", 1.6, false, 0.0},
        BackendCase{"silo_inserts_and_outlet", "bulk/beverloo-small.toml", 1.2, false, 0.0}),
    [](const testing::TestParamInfo<BackendCase>& p) { return std::string(p.param.name); });

} // namespace
} // namespace yuxi
