// Energy conservation and the energy books (docs/models/fish-basin.md section 8).
//  - No damping, no friction: total mechanical energy is conserved up to the O(dt^2) error of
//    velocity Verlet: halving dt divides the largest deviation by about 4.
//  - With damping and friction: mechanical + dissipated stays constant. The dashpot power is
//    booked at the velocities of the force evaluation, which is first-order accurate: measured,
//    the books close to 0.2 % of the dissipated energy at t_c/dt = 50, 0.09 % at 100, 0.04 % at
//    200 (tolerance 0.5 %, and at least 1.6 times better at half the step). Coulomb sliding alone
//    closes to second order (0.06 %, 0.014 %, 0.003 %).
//  - With a vibrating floor: mechanical + dissipated - wall work stays constant likewise.
#include "core/random.hpp"
#include "core/units.hpp"
#include "test_support.hpp"
#include "validation/collision_probe.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

// 125 polydisperse grains with random velocities in a closed box (flat walls on every face).
Simulation gas(const test::Coeffs& c, double dt, double floor_amplitude = 0.0,
               std::uint64_t seed = 42) {
  auto cfg = test::open_box(4.0, {0, 0, -1.0}, dt);
  cfg.box.boundary = {Boundary::wall, Boundary::wall, Boundary::wall};
  cfg.skin = 0.2;
  const auto specs = test::gas_grains(seed);
  std::vector<PlaneWall> planes;
  if (floor_amplitude > 0) {
    cfg.box.boundary[2] = Boundary::open;
    cfg.box.hi.z = 20;
    PlaneWall floor = test::plane({0, 0, -4}, {0, 0, 1});
    floor.amplitude = floor_amplitude;
    floor.omega = 20.0;
    planes.push_back(floor);
  }
  return Simulation(cfg, test::store_of(specs), planes, {}, test::linear_law(c));
}

// t_c of the stiffest contact here: a light grain (m = 0.35^3) against a wall.
double contact_time(double k_n) {
  return pi / std::sqrt(k_n / (0.35 * 0.35 * 0.35));
}

// The gas is chaotic: at dt and dt/2 it follows different trajectories after a few collisions,
// and the largest departure of one run is that of its hardest collision, so the ratio of one
// pair of runs scatters from about 2 to 8 with the round-off of the compiler. Summed over
// several gases, the departures average over many collisions and the ratio is the method's
// (measured: 3.8 with GCC -O3, 3.5 with clang -O1 under the sanitizers).
TEST(Energy, ConservedToSecondOrderWithoutDampingOrFriction) {
  const test::Coeffs c{1e4, 0, 0, 0, 0, 0};
  const double dt = contact_time(c.k_n) / 40;
  double err_a = 0, err_b = 0, e0 = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    Simulation a = gas(c, dt, 0.0, seed), b = gas(c, dt / 2, 0.0, seed);
    e0 += a.energies().mechanical();
    const double da = test::books_drift(a, 1.0), db = test::books_drift(b, 1.0);
    err_a += da, err_b += db;
  }
  EXPECT_LT(err_a / e0, 2e-3);
  EXPECT_GT(err_a / err_b, 3.0) << "error must fall like dt^2";
  EXPECT_LT(err_a / err_b, 5.5);
}

TEST(Energy, CoulombSlidingIsBookedToSecondOrder) {
  const test::Coeffs c{1e4, 2.5e3, 0.0, 0.0, 0.5, 0.3};
  const double dt = contact_time(c.k_n) / 50;
  Simulation a = gas(c, dt), b = gas(c, dt / 2);
  const double err_a = test::books_drift(a, 2.0), err_b = test::books_drift(b, 2.0);
  EXPECT_LT(err_a / a.energies().dissipated, 2e-3);
  EXPECT_GT(err_a / err_b, 3.0);
}

TEST(Energy, BooksCloseWithDampingAndFriction) {
  const test::Coeffs c{1e4, 2.5e3, 20.0, 10.0, 0.5, 0.3};
  const double dt = contact_time(c.k_n) / 50;
  Simulation a = gas(c, dt), b = gas(c, dt / 2);
  const double err_a = test::books_drift(a, 2.0);
  const double err_b = test::books_drift(b, 2.0);
  const double dissipated = a.energies().dissipated;
  ASSERT_GT(dissipated, 0.3 * a.energies().mechanical()); // the test means something
  EXPECT_LT(err_a / dissipated, 5e-3);
  EXPECT_GT(err_a / err_b, 1.6) << "the books must close better at a smaller step";
}

TEST(Energy, BooksCloseWithAVibratingFloor) {
  const test::Coeffs c{1e4, 2.5e3, 20.0, 10.0, 0.5, 0.3};
  const double dt = contact_time(c.k_n) / 50;
  Simulation sim = gas(c, dt, 0.2);
  const double err = test::books_drift(sim, 3.0);
  const auto e = sim.energies();
  ASSERT_GT(e.wall_work, 0.0);
  EXPECT_LT(err / (e.dissipated + std::abs(e.wall_work)), 5e-3);
}

TEST(Momentum, ConservedInAFrictionalDampedCollision) {
  auto cfg = test::open_box(5.0, {}, 1e-5);
  Simulation sim(
      cfg,
      test::store_of({test::sphere({0.3, 0.1, 0.6}, 0.6, 1.3, {-0.2, 0.4, -1.0}, {1, 2, 3}),
                      test::sphere({0, 0, -0.5}, 0.5, 0.7, {0.1, 0, 0.8}, {-2, 0, 1})}),
      {}, {}, test::linear_law({2e5, 5e4, 30.0, 10.0, 0.5, 0.3}));
  auto momentum = [&] {
    Vec3 p;
    for (std::size_t i = 0; i < 2; ++i) p += sim.particles().mass[i] * sim.particles().v[i];
    return p;
  };
  const Vec3 p0 = momentum();
  const auto rec = test::collide(sim, 100000);
  ASSERT_GT(rec.contact_time, 0);
  const Vec3 p1 = momentum();
  EXPECT_NEAR(p1.x, p0.x, 1e-12);
  EXPECT_NEAR(p1.y, p0.y, 1e-12);
  EXPECT_NEAR(p1.z, p0.z, 1e-12);
}

} // namespace
} // namespace yuxi
