// Hertz-Mindlin with Tsuji damping (contact/hertz_mindlin.hpp), law by law against its closed
// forms: E* and G* mixed from two materials; at rest the Hertz force (4/3) E* sqrt(R*)
// delta^{3/2} and energy (8/15) E* sqrt(R*) delta^{5/2}; the Mindlin tangential stiffness
// 8 G* sqrt(R* delta) below the Coulomb limit and mu F_n beyond it; and through the engine, the
// restitution e at every impact speed and the contact time 2.94 delta_max / v.
#include "contact/hertz_mindlin.hpp"
#include "core/units.hpp"
#include "test_support.hpp"
#include "validation/collision_probe.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

constexpr double youngs = 1e6, poisson = 0.3;

// A contact between two grains of radius 0.5 (R* = 0.25, m* = 0.5) along +z at `overlap`, with
// the velocity `v_rel` of i relative to j at the centres.
ContactGeometry contact(double overlap, Vec3 v_rel = {}, double dt = 1e-5) {
  ContactGeometry g;
  g.n = {0, 0, 1};
  g.overlap = overlap;
  g.distance = 1.0 - overlap;
  g.v_rel = v_rel;
  g.a_i = g.a_j = 0.5;
  g.m_eff = 0.5;
  g.r_eff = 0.25;
  g.dt = dt;
  return g;
}

TEST(HertzMindlinContact, MixesTheMaterialsElasticConstants) {
  const auto c = HertzMindlin::mix(youngs, poisson, 2 * youngs, 0.25, 0.8, 0.5);
  EXPECT_NEAR(c.e_star, 1 / ((1 - 0.09) / youngs + (1 - 0.0625) / (2 * youngs)), 1e-9 * youngs);
  const double g1 = youngs / (2 * 1.3), g2 = 2 * youngs / (2 * 1.25);
  EXPECT_NEAR(c.g_star, 1 / ((2 - 0.3) / g1 + (2 - 0.25) / g2), 1e-9 * youngs);
  // against a rigid wall only the grain yields
  const auto wall = HertzMindlin::mix(youngs, poisson, INFINITY, poisson, 0.8, 0.5);
  EXPECT_DOUBLE_EQ(wall.e_star, youngs / (1 - poisson * poisson));
  EXPECT_THROW(HertzMindlin::mix(INFINITY, poisson, INFINITY, poisson, 0.8, 0.5),
               std::invalid_argument);
}

TEST(HertzMindlinContact, AtRestTheForceAndEnergyAreHertzs) {
  const auto c = HertzMindlin::mix(youngs, poisson, youngs, poisson, 0.7, 0.5);
  for (const double overlap : {1e-4, 1e-3, 1e-2}) {
    HertzMindlin::State s;
    const ContactResult r = HertzMindlin::evaluate(contact(overlap), c, s);
    const double hertz = 4.0 / 3.0 * c.e_star * std::sqrt(0.25) * std::pow(overlap, 1.5);
    EXPECT_NEAR(r.force.z, hertz, 1e-12 * hertz);
    EXPECT_NEAR(r.elastic, 0.4 * hertz * overlap, 1e-12 * hertz * overlap);
    EXPECT_EQ(r.force.x, 0.0);
    EXPECT_EQ(r.dissipated, 0.0);
  }
}

TEST(HertzMindlinContact, TheTangentialSpringIsMindlinsUntilItSlides) {
  const auto c = HertzMindlin::mix(youngs, poisson, youngs, poisson, 0.7, 0.5);
  const double overlap = 1e-3, dt = 1e-5;
  const double s_t = 8 * c.g_star * std::sqrt(0.25 * overlap);
  const double f_n = 4.0 / 3.0 * c.e_star * std::sqrt(0.25) * std::pow(overlap, 1.5);
  HertzMindlin::State s;
  // a slow tangential drift: the spring stretches by v dt a step, its force -S_t s (the
  // dashpot adds eta_t v, small at this speed)
  const double v = 1e-4;
  double stretch = 0;
  for (int k = 0; k < 10; ++k) {
    const ContactResult r = HertzMindlin::evaluate(contact(overlap, {v, 0, 0}, dt), c, s);
    stretch += v * dt;
    const double eta_t = -2 * std::sqrt(5.0 / 6.0) * c.beta * std::sqrt(s_t * 0.5);
    EXPECT_NEAR(r.force.x, -s_t * stretch - eta_t * v, 1e-9 * s_t * stretch);
  }
  // a fast one slides: the force is mu F_n
  ContactResult r;
  for (int k = 0; k < 2000; ++k)
    r = HertzMindlin::evaluate(contact(overlap, {1.0, 0, 0}, dt), c, s);
  EXPECT_NEAR(std::abs(r.force.x), 0.5 * f_n, 1e-9 * f_n);
}

// Two grains (radius 0.5, mass 1) head-on at relative speed 2 v0.
Simulation head_on(const HertzMindlin::Coeffs& c, double v0, double dt) {
  auto cfg = test::open_box(4.0, {0, 0, 0}, dt);
  const double gap = 2 * v0 * 200 * dt;
  ContactLaw<HertzMindlin> law{PairTable<HertzMindlin::Coeffs>(1)};
  law.coeffs.set(0, 0, c);
  return Simulation(cfg,
                    test::store_of({test::sphere({-0.5 - gap / 2, 0, 0}, 0.5, 1.0, {v0, 0, 0}),
                                    test::sphere({0.5 + gap / 2, 0, 0}, 0.5, 1.0, {-v0, 0, 0})}),
                    {}, {}, law);
}

TEST(HertzMindlinContact, RestitutionIsTheSameAtEverySpeedAndTheContactLastsAsHertzSays) {
  for (const double e : {0.5, 0.9}) {
    const auto c = HertzMindlin::mix(youngs, poisson, youngs, poisson, e, 0.0);
    for (const double v0 : {0.01, 0.1, 1.0}) {
      SCOPED_TRACE(testing::Message() << "e = " << e << ", v0 = " << v0);
      const double t_c = HertzMindlin::contact_time(c, 0.5, 0.25, 2 * v0);
      Simulation sim = head_on(c, v0, t_c / 2000);
      const auto rec = test::collide(sim, 40000);
      ASSERT_GT(rec.contact_time, 0.0);
      EXPECT_NEAR(-rec.v_after.x / rec.v_before.x, e, 2e-3 * e);
      if (e == 0.9) { // (Hertz's t_c is the elastic one; damping lengthens it a little)
        EXPECT_NEAR(rec.contact_time, t_c, 0.03 * t_c);
      }
    }
  }
}

TEST(HertzMindlinContact, ReleaseReturnsWhatTheSpringsHeld) {
  const auto c = HertzMindlin::mix(youngs, poisson, youngs, poisson, 0.7, 0.5);
  HertzMindlin::State s;
  ContactResult r;
  for (int k = 0; k < 5; ++k) r = HertzMindlin::evaluate(contact(1e-3, {1e-3, 0, 0}), c, s);
  const double held = s.tangential.stored();
  ASSERT_GT(held, 0.0);
  EXPECT_DOUBLE_EQ(HertzMindlin::release(c, s), held);
  EXPECT_EQ(s, HertzMindlin::State{});
}

} // namespace
} // namespace yuxi
