// The thermodynamic contact model in the DEM engine (docs/models/thermodynamic-contact.md
// sections 7 and 8): the contact routine against closed forms (T8-T11) and two-grain collisions
// run by the engine against the spec's reference numbers (T1, T2, T4, T6).
#include "contact/contact_model.hpp"
#include "core/random.hpp"
#include "thermo/two_grain.hpp"
#include "validation/binary_collision.hpp"
#include "validation/impact_probe.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

using Coeffs = Thermodynamic::Coeffs;
using State = Thermodynamic::State;

// Model units of the spec's tests: m = 1, a = 0.5 (d = 1), k = (4/3) E* sqrt(R*) = 1.
constexpr double unit_e_star = 1.5;

Coeffs ref_coeffs() {
  Coeffs c;
  c.e_star = unit_e_star;
  return c;
}

// Elastic and viscous parts only: no relaxation by w_R.
Coeffs plain_coeffs(double eta_hat, double eta_power) {
  Coeffs c = ref_coeffs();
  c.eta_hat = eta_hat;
  c.eta_power = eta_power;
  c.lambda_hat = 0;
  return c;
}

AnyContactLaw thermo_law(const Coeffs& c) {
  ContactLaw<Thermodynamic> law{PairTable<Coeffs>(1)};
  law.coeffs.set(0, 0, c);
  return law;
}

// Two unit grains, i at x_i and j at x_j, with the given motion, as the pair loop sees them.
ContactGeometry pair_geometry(Vec3 x_i, Vec3 x_j, Vec3 v_rel, Vec3 w_i, Vec3 w_j, double dt) {
  ContactGeometry g;
  const Vec3 d = x_i - x_j;
  g.distance = norm(d);
  g.n = d / g.distance;
  g.overlap = 1.0 - g.distance;
  g.v_rel = v_rel;
  g.w_i = w_i;
  g.w_j = w_j;
  g.a_i = g.a_j = 0.5;
  g.m_eff = 0.5;
  g.r_eff = 0.25;
  g.dt = dt;
  return g;
}

double elastic(const State& s, double xi = 8.0) {
  return thermo::elastic_energy(1.0, xi, s.un, norm2(s.ut));
}

// T9: a static, prestressed contact relaxes its tangential spring through w_R (40):
// w_R(t) = w_R0 e^{-t/tau}, ln(u_t/u_t0) = -2 tau Lambda kappa sqrt(w_R0) (1 - e^{-t/(2 tau)}).
TEST(ThermoContact, StaticRelaxationFollowsTheClosedForm) {
  const Coeffs c = ref_coeffs();
  const double x0 = 0.01, ut0 = 0.05 * x0, w0 = 1e-3, dt = 0.01;
  State s;
  s.un = -x0;
  s.ut = {0, ut0, 0};
  s.w_relax = w0;
  s.n_prev = {1, 0, 0};
  s.delta_prev = x0;
  s.stored = elastic(s);
  const auto geom = pair_geometry({0.5 - 0.5 * x0, 0, 0}, {-0.5 + 0.5 * x0, 0, 0}, {}, {}, {}, dt);
  const auto co = Thermodynamic::coefficients(c, 0.5, 0.25, 1.0);
  ASSERT_NEAR(co.tau, 5 * std::sqrt(1.0), 1e-12); // t0 = 1 in model units
  const double e0 = elastic(s) + w0;
  double heat = 0;
  const int steps = 2000;
  for (int k = 0; k < steps; ++k) heat += Thermodynamic::evaluate(geom, c, s).dissipated;
  const double t = steps * dt;
  const double kappa = 2.0 / 8.0 * std::sqrt(x0);
  EXPECT_NEAR(s.w_relax, w0 * std::exp(-t / co.tau), 1e-12 * w0);
  const double expected =
      -2 * co.tau * co.lambda * kappa * std::sqrt(w0) * (1 - std::exp(-t / (2 * co.tau)));
  // The exact exponential per step uses w_R at the start of the step: first order in dt/tau.
  EXPECT_NEAR(std::log(s.ut.y / ut0), expected, 2e-3 * std::abs(expected));
  EXPECT_LT(std::log(s.ut.y / ut0), -0.01); // the relaxation is not negligible
  EXPECT_NEAR(heat + elastic(s) + s.w_relax, e0, 1e-13 * e0);
  EXPECT_NEAR(s.un, -x0, 1e-15); // no normal relaxation in the example model
}

// T10: a state outside the stability region (35) returns to its boundary in one step, and the
// released elastic energy is heat.
TEST(ThermoContact, YieldReturnsToTheBoundaryAndBooksHeat) {
  const Coeffs c = plain_coeffs(0, 0.5);
  const double x0 = 0.01, limit = std::sqrt(2 * 8.0) * x0;
  State s;
  s.un = -x0;
  s.ut = {0, 0, 1.5 * limit};
  s.n_prev = {1, 0, 0};
  s.delta_prev = x0;
  s.stored = elastic(s);
  const double before = elastic(s);
  const auto geom =
      pair_geometry({0.5 - 0.5 * x0, 0, 0}, {-0.5 + 0.5 * x0, 0, 0}, {}, {}, {}, 0.01);
  const auto r = Thermodynamic::evaluate(geom, c, s);
  EXPECT_NEAR(norm(s.ut), limit, 1e-15);
  EXPECT_NEAR(r.dissipated, before - elastic(s), 1e-15 * before);
  EXPECT_GT(r.dissipated, 0);
  // On the boundary the Coulomb form (36) holds with equality: |pi_t| = sqrt(2/xi) pi_n.
  const double pi_n = thermo::normal_spring_force(1, 8, s.un, norm2(s.ut));
  const double pi_t = thermo::tangential_stiffness(1, 8, s.un) * norm(s.ut);
  EXPECT_NEAR(pi_t / pi_n, std::sqrt(2 / 8.0), 1e-12);
}

// T8: under random shearing, rolling and squeezing the invariants hold after every step:
// u_n <= 0, pi_n >= 0, |u_t| <= sqrt(2 xi)(-u_n), |pi_t| <= sqrt(2/xi) pi_n; and each step's
// books close: work done on the contact = change of w_el + w_R + heat (to first order in dt).
TEST(ThermoContact, InvariantsHoldUnderRandomDriving) {
  const Coeffs c = ref_coeffs();
  Random rng(7);
  State s;
  const double dt = 0.01;
  double delta = 0.0;
  for (int k = 0; k < 20000; ++k) {
    delta = std::clamp(delta + 2e-5 * (rng.uniform() - 0.45), 1e-6, 0.02);
    const Vec3 axis = normalized(Vec3{1, 0.3 * (rng.uniform() - 0.5), 0.3 * (rng.uniform() - 0.5)});
    const Vec3 x_i = (0.5 - 0.5 * delta) * axis;
    const Vec3 v{0, 0.01 * (rng.uniform() - 0.5), 0.01 * (rng.uniform() - 0.5)};
    const Vec3 w_i{0, 0.01 * (rng.uniform() - 0.5), 0}, w_j{0, 0, 0.01 * (rng.uniform() - 0.5)};
    const auto r = Thermodynamic::evaluate(pair_geometry(x_i, -x_i, v, w_i, w_j, dt), c, s);
    ASSERT_LE(s.un, 0.0);
    ASSERT_GE(s.w_relax, 0.0);
    ASSERT_GE(r.dissipated, -1e-18);
    const double limit = thermo::yield_limit(8, s.un);
    ASSERT_LE(norm(s.ut), limit * (1 + 1e-12)) << "step " << k;
    const double pi_n = thermo::normal_spring_force(1, 8, s.un, norm2(s.ut));
    const double pi_t = thermo::tangential_stiffness(1, 8, s.un) * norm(s.ut);
    ASSERT_GE(pi_n, 0.0);
    ASSERT_LE(pi_t, std::sqrt(2 / 8.0) * pi_n * (1 + 1e-12) + 1e-300);
  }
}

// T11: a prestressed contact carried through a rigid rotation (v = Omega x r, w_i = w_j =
// Omega) keeps |u_t|, u_n, w_el and |F|, its force turns with n, and it makes no heat.
TEST(ThermoContact, RigidRotationMovesNoSpring) {
  Coeffs c = ref_coeffs();
  c.lambda_hat = 0;
  const double delta = 0.01, dt = 0.01;
  const Vec3 omega{0, 0, 0.05}; // about z, perpendicular to the initial normal x
  State s;
  s.un = -delta;
  s.ut = {0, 0.3 * thermo::yield_limit(8, s.un), 0};
  s.n_prev = {1, 0, 0};
  s.delta_prev = delta;
  s.stored = elastic(s);
  const double ut0 = norm(s.ut), w0 = elastic(s);
  double f0 = 0, heat = 0;
  for (int k = 0; k <= 400; ++k) {
    const double angle = omega.z * k * dt;
    const Vec3 n{std::cos(angle), std::sin(angle), 0};
    const Vec3 x_i = (0.5 - 0.5 * delta) * n;
    // v_i - v_j = Omega x (x_i - x_j)
    const auto r = Thermodynamic::evaluate(
        pair_geometry(x_i, -x_i, cross(omega, 2.0 * x_i), omega, omega, dt), c, s);
    if (k == 0) f0 = norm(r.force);
    heat += r.dissipated;
    EXPECT_NEAR(norm(s.ut), ut0, 1e-12 * ut0);
    EXPECT_NEAR(s.un, -delta, 1e-15);
    EXPECT_NEAR(norm(r.force), f0, 1e-10 * f0);
    EXPECT_NEAR(dot(r.force, n), thermo::normal_spring_force(1, 8, s.un, ut0 * ut0), 1e-10 * f0);
    EXPECT_NEAR(dot(s.ut, n), 0.0, 1e-15);
  }
  EXPECT_NEAR(elastic(s), w0, 1e-12 * w0);
  EXPECT_NEAR(heat, 0.0, 1e-12 * w0);
}

// Mirrored states describe the same contact from the partner's side.
TEST(ThermoContact, MirroredStateGivesTheOppositeForce) {
  const Coeffs c = ref_coeffs();
  State s;
  s.un = -0.01;
  s.ut = {0, 0.02, 0.01};
  s.n_prev = {1, 0, 0};
  s.delta_prev = 0.01;
  s.w_relax = 1e-8;
  State m = s.mirrored();
  const Vec3 x{0.495, 0, 0};
  const auto a = Thermodynamic::evaluate(pair_geometry(x, -x, {0, 1e-3, 0}, {}, {}, 0.01), c, s);
  const auto b = Thermodynamic::evaluate(pair_geometry(-x, x, {0, -1e-3, 0}, {}, {}, 0.01), c, m);
  EXPECT_NEAR(norm(a.force + b.force), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(a.elastic, b.elastic);
  EXPECT_DOUBLE_EQ(a.dissipated, b.dissipated);
}

// Two unit grains collide in the engine, each at v0, centres offset by b d.
validation::BinaryOutcome collide(const Coeffs& c, double v0, double b, double steps_per_tc,
                                  bool spins = true) {
  validation::BinaryCollision setup;
  setup.law = thermo_law(c);
  setup.v0 = v0;
  setup.impact_parameter = b;
  setup.steps_per_contact = steps_per_tc;
  setup.spins = spins;
  const auto out = validation::collide_binary(setup);
  EXPECT_TRUE(out.separated);
  return out;
}

// T1: no viscosity and no relaxation: Hertz, e = 1 (DEM at t_c/200 to 1e-4).
TEST(ThermoEngine, HertzLimitIsElastic) {
  for (double v0 : {1e-4, 1e-2}) {
    const auto r = collide(plain_coeffs(0, 0.5), v0, 0, 200);
    EXPECT_NEAR(r.e_n, 1.0, 1e-4) << "v0 = " << v0;
    EXPECT_LT(r.max_drift, 1e-4);
  }
}

// T2 (DEM scheme): the books close to O(dt^2) without sliding (<= 5e-5 at t_c/200, /4 per
// halving of dt), to O(dt) with sliding (<= 2e-3 at t_c/200, /2 per halving).
TEST(ThermoEngine, EnergyIdentityHeadOnIsSecondOrder) {
  const auto coarse = collide(ref_coeffs(), 1e-3, 0, 100);
  const auto fine = collide(ref_coeffs(), 1e-3, 0, 200);
  const auto finer = collide(ref_coeffs(), 1e-3, 0, 400);
  EXPECT_LT(fine.max_drift, 5e-5);
  EXPECT_GT(coarse.max_drift / fine.max_drift, 3.0);
  EXPECT_GT(fine.max_drift / finer.max_drift, 3.0);
  EXPECT_GT(fine.peak_relax, 0.05); // w_R is excited in a head-on impact (Fig. 3(d))
  EXPECT_LT(fine.max_mech_rise, 1e-3);
}

TEST(ThermoEngine, EnergyIdentityWithSlidingIsFirstOrder) {
  const auto fine = collide(ref_coeffs(), 1e-3, 0.5, 200);
  const auto finer = collide(ref_coeffs(), 1e-3, 0.5, 400);
  EXPECT_LT(fine.max_drift, 2e-3);
  EXPECT_GT(fine.max_drift / finer.max_drift, 1.6);
  // Equal grains turn equally, in the same sense (spec T13).
  EXPECT_GT(norm(fine.w_after[0]), 0.0);
  EXPECT_NEAR(fine.w_after[0].z, fine.w_after[1].z, 1e-9 * std::abs(fine.w_after[0].z));
}

// T6 in the DEM engine: REF's restitution falls with impact speed (Fig. 4) and matches the
// adaptive reference values (sharp step) to the scheme's accuracy at t_c/200.
TEST(ThermoEngine, RestitutionFallsWithImpactSpeedAsInTheReferenceTable) {
  const double v0s[] = {1e-5, 1e-4, 1e-3, 1e-2, 1e-1};
  const double reference[] = {0.94915, 0.92083, 0.87794, 0.81459, 0.72441};
  double previous = 1.0;
  for (int k = 0; k < 5; ++k) {
    const auto r = collide(ref_coeffs(), v0s[k], 0, 400);
    EXPECT_NEAR(r.e_n, reference[k], 5e-4) << "v0 = " << v0s[k];
    EXPECT_LT(r.e_n, previous);
    previous = r.e_n;
  }
}

// T4: with eta = 2 sqrt(5/6)|beta| sqrt((3/2) k m*) delta^{1/4} the model is Hertz-Mindlin with
// Tsuji damping; its restitution is e_in at every speed, as the engine's Hertz-Mindlin gives.
TEST(ThermoEngine, TsujiViscosityReproducesHertzMindlin) {
  for (double e_in : {0.9, 0.5}) {
    const double le = std::log(e_in), beta = le / std::sqrt(le * le + M_PI * M_PI);
    // eta_hat sqrt(2 m* k) d^{1/4} (delta/d)^{1/4} = 2 sqrt(5/6)|beta| sqrt(3/2) sqrt(k m*)
    // delta^{1/4}
    const Coeffs c = plain_coeffs(std::sqrt(2.5) * std::abs(beta), 0.25);
    for (double v0 : {1e-4, 1e-2}) {
      const auto r = collide(c, v0, 0, 400);
      EXPECT_NEAR(r.e_n, e_in, 2e-3) << "e_in = " << e_in << ", v0 = " << v0;
    }
    // The engine's Hertz-Mindlin with the same E*.
    ContactLaw<HertzMindlin> hm{PairTable<HertzMindlin::Coeffs>(1)};
    hm.coeffs.set(0, 0,
                  HertzMindlin::mix(2 * unit_e_star * (1 - 0.09), 0.3, 2 * unit_e_star * (1 - 0.09),
                                    0.3, e_in, 0));
    validation::Impact setup;
    setup.law = hm;
    setup.dt = Thermodynamic::contact_time(c, 0.5, 0.25, 2e-3) / 400;
    setup.bodies.push_back({{-0.5 - 1e-5, 0, 0}, {1e-3, 0, 0}, {}, 0.5, 1.0});
    setup.bodies.push_back({{0.5 + 1e-5, 0, 0}, {-1e-3, 0, 0}, {}, 0.5, 1.0});
    const auto out = validation::run_impact(setup);
    EXPECT_NEAR(-out.v[0].x / 1e-3, e_in, 2e-3);
    const auto r = collide(c, 1e-3, 0, 400);
    EXPECT_NEAR(r.e_n, -out.v[0].x / 1e-3, 1e-3);
  }
}

// T12: the 3-D engine with all motion in a plane and rotation locked reproduces the exact 2-D
// two-grain solution, head-on and oblique with sliding (first order in dt there).
TEST(ThermoEngine, PlanarMotionWithoutRotationReproducesTheTwoGrainSolver) {
  for (double b : {0.0, 0.5}) {
    const auto exact =
        thermo::collide(thermo::TwoGrainSetup::example(thermo::ExampleModel::ref(), 1e-3, b));
    const auto dem = collide(ref_coeffs(), 1e-3, b, 800, false);
    EXPECT_NEAR(dem.e_n, exact.restitution, 2e-4) << "b = " << b;
    // The engine moves what w_R holds at separation to heat (spec 7, contact life cycle).
    EXPECT_NEAR(dem.heat, (exact.final_heat + exact.final_w_relax) / exact.initial_energy, 2e-3)
        << "b = " << b;
  }
}

} // namespace
} // namespace yuxi
