// Luding's elasto-plastic adhesive law (contact/luding.hpp), branch by branch against its
// closed forms: virgin loading along k1; unloading and reloading along k2(delta_max) from the
// plastic overlap delta_0 = (1 - k1/k2) delta_max; the adhesive limit -kc delta; kp once
// delta_max passes delta_p; and through the engine, the restitution sqrt(k1/kp) of an undamped
// impact that reaches delta_p.
#include "contact/luding.hpp"
#include "core/units.hpp"
#include "test_support.hpp"
#include "validation/collision_probe.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

// Two grains of radius 0.5 along +z (a12 = 0.25, m* = 0.5) at `overlap`.
ContactGeometry contact(double overlap) {
  ContactGeometry g;
  g.n = {0, 0, 1};
  g.overlap = overlap;
  g.distance = 1.0 - overlap;
  g.a_i = g.a_j = 0.5;
  g.m_eff = 0.5;
  g.r_eff = 0.25;
  g.dt = 1e-4;
  return g;
}

Luding::Coeffs plastic(double kc = 0) {
  Luding::Coeffs c;
  c.k1 = 1e4;
  c.kp = 5e4;
  c.kc = kc;
  c.phi_f = 0.05;
  return c;
}

// The force after walking the overlap along `path` (evaluated at each).
double force_after(const Luding::Coeffs& c, Luding::State& s, std::initializer_list<double> path) {
  double f = 0;
  for (const double d : path) f = Luding::evaluate(contact(d), c, s).force.z;
  return f;
}

TEST(LudingContact, LoadsAlongK1AndUnloadsAlongK2FromThePlasticOverlap) {
  const Luding::Coeffs c = plastic();
  const double delta_p = c.kp / (c.kp - c.k1) * c.phi_f * 2 * 0.25; // 0.03125
  Luding::State s;
  // virgin loading
  EXPECT_NEAR(force_after(c, s, {0.001, 0.002, 0.004}), c.k1 * 0.004, 1e-9);
  // unloading from delta_max = 0.004: k2 = k1 + (kp - k1) delta_max / delta_p
  const double k2 = c.k1 + (c.kp - c.k1) * 0.004 / delta_p;
  const double delta_0 = (1 - c.k1 / k2) * 0.004;
  EXPECT_NEAR(force_after(c, s, {0.003}), k2 * (0.003 - delta_0), 1e-9);
  // reloading follows k2 back to the virgin line
  EXPECT_NEAR(force_after(c, s, {0.0035}), k2 * (0.0035 - delta_0), 1e-9);
  EXPECT_NEAR(force_after(c, s, {0.005}), c.k1 * 0.005, 1e-9);
  // beyond delta_p the unloading stiffness is kp
  Luding::State deep;
  force_after(c, deep, {0.01, 0.02, 0.04});
  const double delta_0p = (1 - c.k1 / c.kp) * 0.04;
  EXPECT_NEAR(force_after(c, deep, {0.035}), c.kp * (0.035 - delta_0p), 1e-9);
}

TEST(LudingContact, AdhesionPullsDownToMinusKcDelta) {
  const Luding::Coeffs c = plastic(2e3);
  Luding::State s;
  force_after(c, s, {0.005, 0.01});
  // unloading below delta_0: tension, bounded by -kc delta
  const double f = force_after(c, s, {0.009, 0.008, 0.006, 0.004, 0.002});
  EXPECT_NEAR(f, -c.kc * 0.002, 1e-9);
  // without kc the contact carries no tension
  const Luding::Coeffs loose = plastic(0.0);
  Luding::State t;
  force_after(loose, t, {0.005, 0.01});
  EXPECT_NEAR(force_after(loose, t, {0.009, 0.006, 0.004, 0.002}), 0.0, 1e-12);
}

// Two grains (radius 0.5, mass 1) head-on at relative speed 2 v0, fast enough to pass delta_p.
TEST(LudingContact, AnUndampedImpactPastDeltaPReboundsWithSqrtK1OverKp) {
  const Luding::Coeffs c = plastic();
  const double v0 = 3.0; // delta_max = 2 v0 sqrt(m*/k1) = 0.042 > delta_p = 0.031
  const double dt = Luding::contact_time(c, 0.5, 0.25, 2 * v0) / 2000;
  auto cfg = test::open_box(4.0, {0, 0, 0}, dt);
  ContactLaw<Luding> law{PairTable<Luding::Coeffs>(1)};
  law.coeffs.set(0, 0, c);
  const double gap = 2 * v0 * 100 * dt;
  Simulation sim(cfg,
                 test::store_of({test::sphere({-0.5 - gap / 2, 0, 0}, 0.5, 1.0, {v0, 0, 0}),
                                 test::sphere({0.5 + gap / 2, 0, 0}, 0.5, 1.0, {-v0, 0, 0})}),
                 {}, {}, law);
  const double b0 = sim.energies().balance();
  const auto rec = test::collide(sim, 400000);
  ASSERT_GT(rec.contact_time, 0.0);
  EXPECT_NEAR(-rec.v_after.x / rec.v_before.x, std::sqrt(c.k1 / c.kp), 2e-3);
  // the plastic work is booked
  const auto e = sim.energies();
  EXPECT_NEAR(e.dissipated, (1 - c.k1 / c.kp) * 2 * 0.5 * v0 * v0, 1e-2 * v0 * v0);
  EXPECT_LT(std::abs(e.balance() - b0), 1e-3 * e.dissipated);
}

} // namespace
} // namespace yuxi
