// Small builders shared by the tests: a simulation of a few explicitly placed spheres.
#pragma once

#include "contact/contact_model.hpp"
#include "core/random.hpp"
#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace yuxi::test {

using Coeffs = LinearSpringDashpot::Coeffs;

// One material, one set of linear coefficients for every pair.
inline AnyContactLaw linear_law(const Coeffs& c, std::size_t n_materials = 1) {
  ContactLaw<LinearSpringDashpot> law{PairTable<Coeffs>(n_materials)};
  for (std::size_t a = 0; a < n_materials; ++a)
    for (std::size_t b = a; b < n_materials; ++b) law.coeffs.set(a, b, c);
  return law;
}

inline SimulationConfig open_box(double half_width, Vec3 gravity, double dt) {
  SimulationConfig c;
  c.box.lo = {-half_width, -half_width, -half_width};
  c.box.hi = {half_width, half_width, half_width};
  c.gravity = gravity;
  c.dt = dt;
  c.skin = 0.1;
  return c;
}

inline ParticleSpec sphere(Vec3 x, double radius, double mass, Vec3 v = {}, Vec3 w = {}) {
  ParticleSpec s;
  s.position = x;
  s.velocity = v;
  s.angular_velocity = w;
  s.radius = radius;
  s.mass = mass;
  return s;
}

inline ParticleStore store_of(const std::vector<ParticleSpec>& specs) {
  ParticleStore s;
  GlobalId id = 0;
  for (const auto& p : specs) s.add(p, id++);
  return s;
}

// Two grains (radius 0.5, mass 1) meeting head-on at relative speed 20 on soft springs
// (k_n = 10): the overlap would peak at v sqrt(m_eff / k_n) = 4.5, far beyond the radius.
inline Simulation head_on(double gap, Comm comm = Comm::self()) {
  auto cfg = test::open_box(4.0, {0, 0, 0}, 1e-3);
  cfg.ranks = {comm.size(), 1, 1};
  cfg.rebalance_every = 0; // even cuts in x: the grains meet (at x = 1.5) on the last rank
  const std::vector<ParticleSpec> specs{test::sphere({1.5 - gap / 2, 0, 0}, 0.5, 1.0, {10, 0, 0}),
                                        test::sphere({1.5 + gap / 2, 0, 0}, 0.5, 1.0, {-10, 0, 0})};
  return Simulation(cfg, test::store_of(specs), {}, {}, test::linear_law({10, 0, 0, 0, 0, 0}),
                    comm);
}

// The diagnosis of a run of `steps` steps that fails ("" if it does not).
inline std::string failure_of(Simulation& sim, std::int64_t steps) {
  try {
    sim.run(steps);
  } catch (const SimulationError& e) {
    return e.what();
  }
  return {};
}

// Index of the owned particle with global id `id` (the simulation reorders particles).
inline std::size_t index_of(const Simulation& sim, GlobalId id) {
  const auto& s = sim.particles();
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (s.gid[i] == id) return i;
  return s.size();
}

// 125 polydisperse grains (radius 0.35-0.55, density 1) on a 5 x 5 x 5 lattice in [-3.2, 3.2]^3,
// with random velocities and spins drawn from `seed`.
inline std::vector<ParticleSpec> gas_grains(std::uint64_t seed) {
  Random rng(seed);
  std::vector<ParticleSpec> specs;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) {
        const double r = rng.uniform(0.35, 0.55);
        specs.push_back(sphere({-3.2 + 1.6 * i, -3.2 + 1.6 * j, -3.2 + 1.6 * k}, r, r * r * r,
                               {rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)},
                               {rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3)}));
      }
  return specs;
}

// Largest |balance(t) - balance(0)| of the energy books over a run to `duration`, every step.
inline double books_drift(Simulation& sim, double duration) {
  const double b0 = sim.energies().balance();
  double worst = 0;
  while (sim.time() < duration) {
    sim.step();
    worst = std::max(worst, std::abs(sim.energies().balance() - b0));
  }
  return worst;
}

// A flat wall through `point` with inward `normal`.
inline PlaneWall plane(Vec3 point, Vec3 normal, std::uint8_t material = 0) {
  PlaneWall w;
  w.point = point;
  w.normal = normal / norm(normal);
  w.material = material;
  return w;
}

} // namespace yuxi::test
