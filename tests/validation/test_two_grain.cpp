// The exact two-grain collision of the thermodynamic contact law against the published numbers of
// docs/models/thermodynamic-contact.md, section 8 (tests T1-T7, T14). Unless said otherwise:
// m1 = m2 = 1, a1 = a2 = 0.5 (d = 1), k = 1, m* = 1/2, head-on at +-v0, E0 = m v0^2, sharp step.
// Where the spec prints a number, the tolerance is half a unit of its last printed digit.
#include "thermo/two_grain.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace yuxi::thermo {
namespace {

constexpr double m_eff = 0.5, k = 1;

// Half a unit of the last digit of a printed number, e.g. printed(1e-4) for 0.9491|5.
double printed(double unit) {
  return 0.5 * unit * (1 + 1e-9);
}

// A constant or power-law coefficient c max(delta, 0)^p.
Coefficient power_law(double c, double p) {
  return [c, p](const ContactVariables& v) { return c * std::pow(std::max(v.delta, 0.0), p); };
}

TwoGrainSetup head_on(double v0) {
  TwoGrainSetup s;
  s.v0 = v0;
  return s;
}

// Hertz: delta_max = (5 m* v^2 / (4 k))^{2/5}; t_c = (2 delta_max / v) int_0^1 (1 - x^{5/2})^{-1/2}
// dx = (2 delta_max / v) (2/5) B(2/5, 1/2).
double hertz_overlap(double v, double stiffness = k) {
  return std::pow(5 * m_eff * v * v / (4 * stiffness), 0.4);
}
double hertz_time(double v) {
  const double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
  return 2 * hertz_overlap(v) / v * 0.4 * beta;
}

// T1: Hertz limit (eta = lambda = 0, u_t = 0): e = 1, delta_max and t_c as printed.
TEST(ThermoTwoGrain, T1HertzLimit) {
  struct Row {
    double v0, overlap, time, time_unit;
  };
  for (const Row& row : {Row{1e-4, 9.1028e-4, 13.40, 1e-2}, Row{1e-2, 3.6239e-2, 5.333, 1e-3}}) {
    SCOPED_TRACE(row.v0);
    const double v = 2 * row.v0;
    const TwoGrainResult r = collide(head_on(row.v0));
    EXPECT_NEAR(r.restitution, 1.0, 1e-9);
    EXPECT_NEAR(r.max_overlap / hertz_overlap(v), 1.0, 1e-9);
    EXPECT_NEAR(r.max_overlap, row.overlap, printed(row.overlap * 1e-4));
    EXPECT_NEAR(r.contact_time / hertz_time(v), 1.0, 1e-9);
    EXPECT_NEAR(r.contact_time, row.time, printed(row.time_unit));
    EXPECT_NEAR(r.peak_force / (k * std::pow(hertz_overlap(v), 1.5)), 1.0, 1e-9);
    EXPECT_LE(r.max_energy_error, 1e-9);
  }
}

// T1: along the whole collision u_n = -delta, w_el = (2/5) k delta^{5/2}, f_n = k delta^{3/2}.
TEST(ThermoTwoGrain, T1SeriesFollowsHertz) {
  TwoGrainSetup s = head_on(1e-3);
  const double v = 2 * s.v0, overlap = hertz_overlap(v);
  s.sample_interval = hertz_time(v) / 200;
  const TwoGrainResult r = collide(s);
  ASSERT_GE(r.series.size(), 200u);
  for (const Sample& p : r.series) {
    SCOPED_TRACE(p.t);
    const double delta = std::max(p.delta, 0.0);
    EXPECT_NEAR(p.un, -delta, 1e-9 * overlap);
    EXPECT_NEAR(p.w_el, 0.4 * k * std::pow(delta, 2.5), 1e-9 * r.initial_energy);
    EXPECT_NEAR(p.fn, k * std::pow(delta, 1.5), 1e-9 * k * std::pow(overlap, 1.5));
    EXPECT_EQ(p.ut, 0.0);
  }
}

// The checks of T2 on one run: E_total constant to 1e-9, E_mech non-increasing, Q
// non-decreasing, w_R >= 0, at every step and every sample.
void expect_energy_identity(const TwoGrainResult& r) {
  const double e0 = r.initial_energy;
  EXPECT_LE(r.max_energy_error, 1e-9);
  EXPECT_LE(r.max_mechanical_rise, 1e-12 * e0);
  EXPECT_TRUE(r.heat_monotone);
  EXPECT_GE(r.min_w_relax, 0.0);
  ASSERT_FALSE(r.series.empty());
  for (std::size_t i = 0; i < r.series.size(); ++i) {
    const Sample& p = r.series[i];
    SCOPED_TRACE(p.t);
    EXPECT_NEAR(p.total / e0, 1.0, 1e-9);
    EXPECT_NEAR(p.total, p.kinetic + p.w_el + p.w_relax + p.heat, 1e-15 * e0);
    EXPECT_GE(p.w_relax, 0.0);
    if (i > 0) {
      EXPECT_LE(p.mechanical, r.series[i - 1].mechanical + 1e-12 * e0);
      EXPECT_GE(p.heat, r.series[i - 1].heat - 1e-15 * e0);
    }
  }
}

// T2 (spec 3.5): energy identity, REF head-on, through separation and the decay of w_R.
TEST(ThermoTwoGrain, T2EnergyIdentityHeadOn) {
  TwoGrainSetup s = TwoGrainSetup::example(ExampleModel::ref(), 1e-3);
  s.after_separation = 20;
  s.sample_interval = 0.05;
  const TwoGrainResult r = collide(s);
  expect_energy_identity(r);
  EXPECT_GT(r.final_heat, 0.1 * r.initial_energy);
  EXPECT_EQ(r.slip_phases, 0);
}

// T2 with sliding: REF oblique (b = 0.5), the yield limit (41) active; with it u_t stays inside
// (35) (T8) and heat is released by it.
TEST(ThermoTwoGrain, T2EnergyIdentityObliqueWithYield) {
  TwoGrainSetup s = TwoGrainSetup::example(ExampleModel::ref(), 1e-3, 0.5);
  s.after_separation = 20;
  s.sample_interval = 0.05;
  const TwoGrainResult r = collide(s);
  expect_energy_identity(r);
  EXPECT_GE(r.slip_phases, 1);
  EXPECT_GT(r.yield_heat, 0.01 * r.initial_energy);
  EXPECT_LE(r.max_yield_ratio, 1 + 1e-12);
  EXPECT_LT(r.tangential_restitution, 1.0);
  for (const Sample& p : r.series) {
    const double pi_n = normal_spring_force(k, s.xi, p.un, p.ut * p.ut);
    const double pi_t = tangential_stiffness(k, s.xi, p.un) * std::abs(p.ut);
    EXPECT_LE(pi_t, friction_of(s.xi) * pi_n * (1 + 1e-9) + 1e-300); // Coulomb form (36)
  }
}

// (41) as the paper writes it, a tangential relaxation lambda_Y switched on outside (35), tends
// to the return mapping as lambda_Y grows (section 4): REF oblique, b = 0.5, with the penalty
// lambda_Y max(|u_t| - sqrt(2 xi)(-u_n), 0) added to lambda_t^T instead of the yield limit.
TEST(ThermoTwoGrain, T2YieldLimitIsTheStiffRelaxationLimit) {
  const TwoGrainResult limit = collide(TwoGrainSetup::example(ExampleModel::ref(), 1e-3, 0.5));
  double previous = 1;
  for (const double lambda_y : {1e6, 1e7, 1e8}) {
    SCOPED_TRACE(lambda_y);
    TwoGrainSetup s = TwoGrainSetup::example(ExampleModel::ref(), 1e-3, 0.5);
    s.yield = false;
    const Coefficient relaxation = s.transport.lambda_t_heat;
    const double xi = s.xi;
    s.transport.lambda_t_heat = [=](const ContactVariables& c) {
      const double beyond = std::abs(c.ut) - yield_limit(xi, c.un);
      return relaxation(c) + lambda_y * std::max(beyond, 0.0);
    };
    const TwoGrainResult r = collide(s);
    const double gap = std::abs(r.restitution - limit.restitution);
    EXPECT_LT(gap, previous / 5);
    previous = gap;
    EXPECT_LE(r.max_energy_error, 1e-9);
  }
  EXPECT_LT(previous, 2e-4);
}

// T3: eta = eta_B delta^{1/2} is the viscoelastic sphere of Kuwabara & Kono / Brilliantov:
// 1 - e as tabulated for eta_B = 0.01, and the two-term series
// 1 - e = C1 A alpha^{2/5} v^{1/5} - C2 A^2 alpha^{4/5} v^{2/5} + O(A^3), A = eta_B/k, alpha =
// k/m*.
TEST(ThermoTwoGrain, T3KuwabaraKonoLimit) {
  constexpr double eta_b = 0.01, a = eta_b / k, alpha = k / m_eff;
  struct Row {
    double v0, loss;
  };
  for (const Row& row : {Row{1e-4, 2.7663e-3}, Row{1e-3, 4.3800e-3}, Row{1e-2, 6.9312e-3}}) {
    SCOPED_TRACE(row.v0);
    TwoGrainSetup s = head_on(row.v0);
    s.transport.eta_n_relax = power_law(eta_b, 0.5);
    const TwoGrainResult r = collide(s);
    const double v = 2 * row.v0;
    const double series = 1.15344 * a * std::pow(alpha, 0.4) * std::pow(v, 0.2) -
                          0.79826 * a * a * std::pow(alpha, 0.8) * std::pow(v, 0.4);
    EXPECT_NEAR(1 - r.restitution, row.loss, printed(1e-7));
    EXPECT_NEAR((1 - r.restitution) / series, 1.0, 5e-5); // the O(A^3) remainder
    EXPECT_LE(r.max_energy_error, 1e-9);
  }
}

// T4: Tsuji damping eta_n = 2 sqrt(5/6)|beta| sqrt((3/2) k m*) delta^{1/4},
// beta = ln e_in / sqrt(ln^2 e_in + pi^2), gives e = e_in at every impact speed.
TEST(ThermoTwoGrain, T4TsujiDampingGivesInputRestitution) {
  struct Row {
    double e_in, coefficient;
  };
  for (const Row& row : {Row{0.9, 0.052997}, Row{0.8, 0.112024}, Row{0.5, 0.340662}}) {
    const double log_e = std::log(row.e_in);
    const double beta = log_e / std::sqrt(log_e * log_e + std::numbers::pi * std::numbers::pi);
    const double c = 2 * std::sqrt(5.0 / 6) * std::abs(beta) * std::sqrt(1.5 * k * m_eff);
    EXPECT_NEAR(c, row.coefficient, printed(1e-6));
    for (const double v0 : {1e-4, 1e-2}) {
      SCOPED_TRACE(testing::Message() << "e_in " << row.e_in << ", v0 " << v0);
      TwoGrainSetup s = head_on(v0);
      s.transport.eta_n_heat = power_law(c, 0.25);
      const TwoGrainResult r = collide(s);
      EXPECT_NEAR(r.restitution, row.e_in, 1e-9);
      EXPECT_LE(r.max_energy_error, 1e-9);
    }
  }
}

// T5: constant dashpot eta0 = 1e-3 (E1-like): 1 - e as tabulated, so e grows with v0.
TEST(ThermoTwoGrain, T5ConstantDashpot) {
  struct Row {
    double v0, loss, unit;
  };
  std::vector<double> e;
  for (const Row& row :
       {Row{1e-4, 1.4796e-2, 1e-6}, Row{1e-3, 9.3563e-3, 1e-7}, Row{1e-2, 5.9116e-3, 1e-7}}) {
    SCOPED_TRACE(row.v0);
    TwoGrainSetup s = head_on(row.v0);
    s.transport.eta_n_relax = power_law(1e-3, 0);
    const TwoGrainResult r = collide(s);
    EXPECT_NEAR(1 - r.restitution, row.loss, printed(row.unit));
    EXPECT_LE(r.max_energy_error, 1e-9);
    e.push_back(r.restitution);
  }
  EXPECT_LT(e[0], e[1]);
  EXPECT_LT(e[1], e[2]);
}

// T6: REF head-on e(v0) and peak w_R/E0 as tabulated; e decreases with v0 (the paper's Fig. 4);
// once w_R has decayed (20 tau after separation), Q/E0 = 1 - e^2.
TEST(ThermoTwoGrain, T6ReferenceModelTable) {
  struct Row {
    double v0, e, peak_w_relax;
  };
  const ExampleModel ref = ExampleModel::ref();
  const double tau = ref.tau_hat * Scales::of(k, m_eff, 1).time;
  double previous = 1;
  for (const Row& row :
       {Row{1e-5, 0.94915, 0.0268}, Row{1e-4, 0.92083, 0.0560}, Row{1e-3, 0.87794, 0.1107},
        Row{1e-2, 0.81459, 0.2011}, Row{1e-1, 0.72441, 0.3316}}) {
    SCOPED_TRACE(row.v0);
    TwoGrainSetup s = TwoGrainSetup::example(ref, row.v0);
    s.after_separation = 20 * tau;
    const TwoGrainResult r = collide(s);
    const double e0 = r.initial_energy;
    EXPECT_NEAR(e0, 1.0 * row.v0 * row.v0, 1e-15 * e0);
    EXPECT_NEAR(r.restitution, row.e, printed(1e-5));
    EXPECT_NEAR(r.peak_w_relax / e0, row.peak_w_relax, printed(1e-4));
    EXPECT_LT(r.restitution, previous);
    previous = r.restitution;
    EXPECT_LT(r.final_w_relax / e0, 1e-8);
    EXPECT_NEAR(r.final_heat / e0, 1 - r.restitution * r.restitution, 1e-8);
    EXPECT_LE(r.max_energy_error, 1e-9);
  }
}

// T6, column E1 (eta0 = 0.05, the literal minimal reading): e grows with v0.
TEST(ThermoTwoGrain, T6LiteralMinimalModel) {
  struct Row {
    double v0, e;
  };
  for (const Row& row : {Row{1e-5, 0.22899}, Row{1e-4, 0.43618}, Row{1e-3, 0.60758},
                         Row{1e-2, 0.73593}, Row{1e-1, 0.82629}}) {
    SCOPED_TRACE(row.v0);
    const TwoGrainResult r = collide(TwoGrainSetup::example(ExampleModel::e1(0.05), row.v0));
    EXPECT_NEAR(r.restitution, row.e, printed(1e-5));
  }
}

// T6, REF with the smoothed Heaviside eps = 1e-4; the contact spans delta > -30 eps d.
TEST(ThermoTwoGrain, T6SmoothedReferenceModel) {
  struct Row {
    double v0, e;
  };
  ExampleModel p = ExampleModel::ref();
  p.epsilon = 1e-4;
  for (const Row& row :
       {Row{1e-5, 0.962215}, Row{1e-4, 0.922203}, Row{1e-3, 0.878078}, Row{1e-2, 0.814601}}) {
    SCOPED_TRACE(row.v0);
    const TwoGrainResult r = collide(TwoGrainSetup::example(p, row.v0));
    EXPECT_NEAR(r.restitution, row.e, printed(1e-6));
    EXPECT_LE(r.max_energy_error, 1e-9);
  }
}

// T7: a constant gearbox G = g renormalises the spring: e = 1 and
// delta_max = (5 m* v^2 / (4 g^{5/2} k))^{2/5}.
TEST(ThermoTwoGrain, T7StaticGearbox) {
  for (const double g : {0.5, 0.8}) {
    SCOPED_TRACE(g);
    TwoGrainSetup s = head_on(1e-3);
    s.transport.gear_n = s.transport.gear_t = [g](const ContactVariables&) { return g; };
    const TwoGrainResult r = collide(s);
    EXPECT_NEAR(r.restitution, 1.0, 1e-9);
    EXPECT_NEAR(r.max_overlap / hertz_overlap(2 * s.v0, std::pow(g, 2.5) * k), 1.0, 1e-9);
    EXPECT_LE(r.max_energy_error, 1e-9);
  }
}

// T14: the time series of Fig. 3 (REF, v0 = 1e-3): E_mech falls from E0 to e^2 E0, f_n turns
// slightly negative before separation, w_R decays as e^{-t/tau} after it.
TEST(ThermoTwoGrain, T14Fig3TimeSeries) {
  TwoGrainSetup s = TwoGrainSetup::example(ExampleModel::ref(), 1e-3);
  const double tau = s.transport.tau;
  s.after_separation = 2 * tau;
  s.sample_interval = 0.01;
  const TwoGrainResult r = collide(s);
  const double e0 = r.initial_energy;
  EXPECT_NEAR(r.series.front().mechanical / e0, 1.0, 1e-15);
  EXPECT_NEAR(r.series.back().mechanical / e0, r.restitution * r.restitution, 1e-9);
  double min_force = 0;
  for (const Sample& p : r.series) min_force = std::min(min_force, p.fn);
  EXPECT_LT(min_force, 0.0);
  EXPECT_GT(min_force, -0.02 * r.peak_force);
  const Sample* first_apart = nullptr;
  for (const Sample& p : r.series) {
    if (p.t <= r.contact_time) continue;
    if (!first_apart) first_apart = &p;
    EXPECT_EQ(p.fn, 0.0);
    EXPECT_NEAR(p.w_relax / first_apart->w_relax, std::exp(-(p.t - first_apart->t) / tau), 1e-9);
  }
  ASSERT_NE(first_apart, nullptr);
}

TEST(ThermoTwoGrain, RejectsSetupsThatCannotCollide) {
  TwoGrainSetup s;
  s.impact_parameter = 1.0; // the grains miss each other
  EXPECT_THROW(collide(s), std::invalid_argument);
  s = TwoGrainSetup{};
  s.transport.gear_n = nullptr;
  EXPECT_THROW(collide(s), std::invalid_argument);
}

} // namespace
} // namespace yuxi::thermo
