// Every contact model keeps the energy books, and the optional parts behave as their closed
// forms say: rolling resistance stops a rolling sphere at (5/7) mu_r g, Luding's adhesion
// holds a contact open under tension.
#include "core/random.hpp"
#include "core/units.hpp"
#include "test_support.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <ostream>

namespace yuxi {
namespace {

// 125 polydisperse grains with random velocities and spins in a walled box under gravity.
Simulation gas(const AnyContactLaw& law, double dt) {
  auto cfg = test::open_box(4.0, {0, 0, -1.0}, dt);
  cfg.box.boundary = {Boundary::wall, Boundary::wall, Boundary::wall};
  const auto specs = test::gas_grains(7);
  return Simulation(cfg, test::store_of(specs), {}, {}, law);
}

AnyContactLaw hertz() {
  ContactLaw<HertzMindlin> law{PairTable<HertzMindlin::Coeffs>(1)};
  law.coeffs.set(0, 0, HertzMindlin::mix(1e5, 0.3, 1e5, 0.3, 0.7, 0.4));
  return law;
}

AnyContactLaw luding() {
  Luding::Coeffs c;
  c.k1 = 5e3;
  c.kp = 2e4;
  c.kc = 1e3;
  c.phi_f = 0.05;
  c.gamma_n = 5;
  c.k_t = 2e3;
  c.gamma_t = 2;
  c.mu_s = 0.6;
  c.mu_d = 0.4;
  c.k_r = 1e3;
  c.gamma_r = 1;
  c.mu_r = 0.1;
  c.k_o = 1e3;
  c.gamma_o = 1;
  c.mu_o = 0.1;
  ContactLaw<Luding> law{PairTable<Luding::Coeffs>(1)};
  law.coeffs.set(0, 0, c);
  return law;
}

// Hertz-Mindlin with rolling resistance (`model`: elastic_plastic or constant_torque).
AnyContactLaw hertz_rolling(RollingModel model, double mu_r = 0.1, double youngs = 1e5) {
  ContactLaw<HertzMindlin> law{PairTable<HertzMindlin::Coeffs>(1)};
  HertzMindlin::Coeffs c = HertzMindlin::mix(youngs, 0.3, youngs, 0.3, 0.7, 0.8);
  c.mu_r = mu_r;
  c.rolling_model = model;
  law.coeffs.set(0, 0, c);
  return law;
}
AnyContactLaw hertz_epsd() {
  return hertz_rolling(RollingModel::elastic_plastic);
}
AnyContactLaw hertz_torque() {
  return hertz_rolling(RollingModel::constant_torque);
}

AnyContactLaw linear_rolling() {
  test::Coeffs c{1e4, 2.5e3, 20.0, 10.0, 0.5, 0.3};
  c.k_r = 1e3;
  c.gamma_r = 5;
  c.mu_r = 0.1;
  return test::linear_law(c);
}

struct ModelCase {
  const char* name;
  AnyContactLaw (*law)();
  double dt;
};
// ctest lists a case by its name and this, not by a dump of the parameter's bytes.
void PrintTo(const ModelCase& c, std::ostream* os) {
  *os << c.name;
}

class EnergyBooks : public ::testing::TestWithParam<ModelCase> {};

// The books close to within 1 % of the energy dissipated at the step given, and better at
// half the step (the dashpots are booked to first order).
TEST_P(EnergyBooks, CloseForEveryModel) {
  const auto& m = GetParam();
  Simulation a = gas(m.law(), m.dt), b = gas(m.law(), m.dt / 2);
  const double err_a = test::books_drift(a, 2.0), err_b = test::books_drift(b, 2.0);
  const double dissipated = a.energies().dissipated;
  ASSERT_GT(dissipated, 0.2 * a.energies().mechanical());
  EXPECT_LT(err_a / dissipated, 1e-2);
  EXPECT_LT(err_b, err_a);
}

INSTANTIATE_TEST_SUITE_P(Models, EnergyBooks,
                         ::testing::Values(ModelCase{"hertz_mindlin", hertz, 1e-4},
                                           ModelCase{"luding", luding, 2e-4},
                                           ModelCase{"linear_rolling", linear_rolling, 2e-4},
                                           ModelCase{"hertz_epsd", hertz_epsd, 1e-4},
                                           ModelCase{"hertz_constant_torque", hertz_torque, 1e-4}),
                         [](const ::testing::TestParamInfo<ModelCase>& p) {
                           return std::string(p.param.name);
                         });

// A sphere rolling without slip on a level plane with a saturated rolling slider feels the
// torque mu_r m g a (a = R against a flat wall) and decelerates at (5/7) mu_r g.
TEST(RollingResistance, StopsARollingSphereAtFiveSeventhsMuRG) {
  test::Coeffs c{1e5, 2.0 / 7.0 * 1e5, 30.0, 150.0, 0.8, 0.8};
  c.k_r = 1e4;
  c.mu_r = 0.05;
  auto cfg = test::open_box(20, {0, 0, -1}, 0.02 * pi / std::sqrt(1e5));
  const double v0 = 1.0;
  Simulation sim(
      cfg, test::store_of({test::sphere({0, 0, 1.0 - 1e-5}, 1.0, 1.0, {v0, 0, 0}, {0, v0, 0})}),
      {test::plane({0, 0, 0}, {0, 0, 1})}, {}, test::linear_law(c));
  const double b0 = sim.energies().balance();
  sim.run(std::llround(1.0 / cfg.dt));
  const double v1 = sim.particles().v[0].x, t1 = sim.time();
  sim.run(std::llround(2.0 / cfg.dt));
  const double decel = (v1 - sim.particles().v[0].x) / (sim.time() - t1);
  EXPECT_NEAR(decel, 5.0 / 7.0 * c.mu_r, 2e-3 * c.mu_r);
  EXPECT_NEAR(sim.particles().v[0].x - sim.particles().w[0].y, 0.0, 1e-4); // still rolling
  // The rolling slider's dissipation is what the sphere lost.
  const auto e = sim.energies();
  ASSERT_GT(e.dissipated, 0.05);
  EXPECT_LT(std::abs(e.balance() - b0), 1e-3 * e.dissipated);
}

// A sphere (R = 1, m = 1, g = 1) set rolling without slip at v0 = 1 on a level plane: each
// rolling-resistance model resists with the torque mu_r R m g once its spring has yielded, so
// the sphere decelerates at (5/7) mu_r g and stops after 7 v0^2 / (10 mu_r g) (Ai et al. 2011,
// model A; model C once sliding). The linear law's constant torque, and Hertz-Mindlin's
// constant torque and elastic-plastic spring (k_r = 2.25 mu_r^2 S_n).
struct RollingCase {
  const char* name;
  AnyContactLaw law;
};
void PrintTo(const RollingCase& c, std::ostream* os) {
  *os << c.name;
}
class RollingStop : public ::testing::TestWithParam<RollingCase> {};

TEST_P(RollingStop, TheSphereStopsWhereTheTorqueSays) {
  const double mu_r = 0.05, v0 = 1.0, dt = 1e-4;
  auto cfg = test::open_box(30, {0, 0, -1}, dt);
  Simulation sim(
      cfg, test::store_of({test::sphere({-20, 0, 1.0 - 1e-5}, 1.0, 1.0, {v0, 0, 0}, {0, v0, 0})}),
      {test::plane({0, 0, 0}, {0, 0, 1})}, {}, GetParam().law);
  const double b0 = sim.energies().balance();
  while (sim.particles().v[0].x > 1e-3 * v0 && sim.time() < 40) sim.step();
  const double travelled = sim.particles().x[0].x + 20;
  // (14.000 for each when written)
  EXPECT_NEAR(travelled, 7 * v0 * v0 / (10 * mu_r), 1e-3 * 7 * v0 * v0 / (10 * mu_r));
  const auto e = sim.energies();
  EXPECT_LT(std::abs(e.balance() - b0), 1e-3 * e.dissipated); // the torque's work is booked
}

AnyContactLaw linear_torque() {
  test::Coeffs c{1e5, 2.0 / 7.0 * 1e5, 30.0, 150.0, 0.8, 0.8};
  c.mu_r = 0.05;
  c.rolling_model = RollingModel::constant_torque;
  return test::linear_law(c);
}

INSTANTIATE_TEST_SUITE_P(
    Models, RollingStop,
    ::testing::Values(RollingCase{"linear_constant_torque", linear_torque()},
                      RollingCase{"hertz_constant_torque",
                                  hertz_rolling(RollingModel::constant_torque, 0.05, 1e7)},
                      RollingCase{"hertz_elastic_plastic",
                                  hertz_rolling(RollingModel::elastic_plastic, 0.05, 1e7)}),
    [](const ::testing::TestParamInfo<RollingCase>& p) { return std::string(p.param.name); });

// On a slope of angle theta, the rolling torque holds a sphere at rest while it can balance the
// friction that holds its centre, m g sin(theta) R <= mu_r R m g cos(theta): up to
// tan(theta) = mu_r. The elastic-plastic springs hold it (linear with k_r, Hertz-Mindlin's own
// stiffness); beyond, it rolls away.
TEST(RollingResistance, HoldsASphereOnASlopeUpToTanThetaMuR) {
  const double mu_r = 0.1;
  test::Coeffs lin{1e5, 2.0 / 7.0 * 1e5, 30.0, 150.0, 0.8, 0.8};
  lin.k_r = 2.25 * mu_r * mu_r * lin.k_n;
  lin.gamma_r = 10;
  lin.mu_r = mu_r;
  for (const auto& [name, law] :
       {std::pair{"linear", test::linear_law(lin)},
        std::pair{"hertz", hertz_rolling(RollingModel::elastic_plastic, mu_r, 1e7)}})
    for (const double ratio : {0.7, 1.3}) {
      const double theta = std::atan(ratio * mu_r);
      auto cfg = test::open_box(30, {std::sin(theta), 0, -std::cos(theta)}, 1e-4);
      Simulation sim(cfg, test::store_of({test::sphere({0, 0, 1.0 - 1e-5}, 1.0, 1.0)}),
                     {test::plane({0, 0, 0}, {0, 0, 1})}, {}, law);
      sim.run(50000); // t = 5
      const double x5 = sim.particles().x[0].x;
      sim.run(50000); // t = 10
      const double moved = sim.particles().x[0].x - x5;
      if (ratio < 1)
        EXPECT_LT(std::abs(moved), 1e-4) << name << " held at tan(theta) = " << ratio << " mu_r";
      else
        EXPECT_GT(moved, 0.1) << name << " rolls at tan(theta) = " << ratio << " mu_r";
    }
}

// Luding's adhesion: pulled apart slowly, the contact holds until the tension reaches the
// adhesive branch -kc delta; without kc it lets go at once.
TEST(LudingAdhesion, HoldsTheContactUnderTension) {
  auto make = [](double kc) {
    Luding::Coeffs c;
    c.k1 = 1e4;
    c.kp = 5e4;
    c.kc = kc;
    c.phi_f = 1e-3;
    ContactLaw<Luding> law{PairTable<Luding::Coeffs>(1)};
    law.coeffs.set(0, 0, c);
    return law;
  };
  for (double kc : {0.0, 2e4}) {
    Luding::State s;
    ContactGeometry g;
    g.n = {0, 0, 1};
    g.a_i = g.a_j = 1.0;
    g.r_eff = 0.5;
    g.m_eff = 0.5;
    g.dt = 1e-4;
    const ContactLaw<Luding> law = make(kc);
    const Luding::Coeffs& c = law.coeffs(0, 0);
    // load to 0.01, then unload in small steps and record the most tensile force
    double most_tensile = 0;
    for (int k = 1; k <= 200; ++k) {
      g.overlap = k <= 100 ? 1e-4 * k : 1e-2 - 1e-4 * (k - 100);
      if (g.overlap <= 0) break;
      const auto r = Luding::evaluate(g, c, s);
      most_tensile = std::min(most_tensile, r.force.z);
    }
    if (kc == 0) {
      EXPECT_NEAR(most_tensile, 0.0, 1e-9);
    } else {
      EXPECT_LT(most_tensile, -1.0); // pulls
    }
  }
}

} // namespace
} // namespace yuxi
