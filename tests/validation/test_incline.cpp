// A sphere on an incline and on a flat plane under gravity (validation.md L9, L10):
//  - rolls without slip at a = (5/7) g sin(theta) when tan(theta) <= 3.5 mu_s;
//  - slides at a = g (sin(theta) - mu_d cos(theta)) when tan(theta) > 3.5 mu_s;
//  - in the band 3.5 mu_d < tan(theta) <= 3.5 mu_s: rolls from rest, keeps sliding if launched
//    with slip (the separate mu_s / mu_d of the paper's law);
//  - a sliding sphere on a level plane ends rolling at v = (5/7) v0 after t_s = 2 v0/(7 mu_d g).
// The incline is a level plane with gravity tilted by theta about y (downhill is +x).
#include "core/units.hpp"
#include "test_support.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

struct Incline {
  double theta_deg;
  double mu_s, mu_d;
  double v0 = 0.0;      // initial downhill speed, no spin: slip
  double gamma_t = 0.0; // tangential damping: 0 where the sphere slides, so that friction is
                        // exactly mu_d |F_n|; near critical (150) where it rolls, so that the
                        // tangential spring, loaded suddenly at release, does not overshoot

  Simulation make() const {
    const double th = theta_deg * pi / 180, g = 1.0, k_n = 1e5, m = 1.0, r = 1.0;
    // Start at the static overlap, at rest along the normal.
    const double overlap = m * g * std::cos(th) / k_n;
    // gamma_n settles the normal motion.
    const test::Coeffs c{k_n, 2.0 / 7.0 * k_n, 30.0, gamma_t, mu_s, mu_d};
    auto cfg =
        test::open_box(10, {g * std::sin(th), 0, -g * std::cos(th)}, 0.02 * pi / std::sqrt(k_n));
    cfg.box.hi.x = 50; // room to roll downhill
    return Simulation(cfg, test::store_of({test::sphere({0, 0, r - overlap}, r, m, {v0, 0, 0})}),
                      {test::plane({0, 0, 0}, {0, 0, 1})}, {}, test::linear_law(c));
  }
};

// Downhill acceleration: least-squares slope of v(t) over 1 <= t <= 2, after the start-up
// transient (the fit also averages out what is left of the tangential spring's oscillation).
double acceleration(Simulation& sim) {
  sim.run(std::llround(1.0 / sim.config().dt));
  double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
  while (sim.time() < 2.0) {
    sim.step();
    const double t = sim.time(), v = sim.particles().v[0].x;
    n += 1, st += t, sv += v, stt += t * t, stv += t * v;
  }
  return (n * stv - st * sv) / (n * stt - st * st);
}

TEST(Incline, RollsAtFiveSeventhsGSinTheta) {
  Simulation sim = Incline{20.0, 0.5, 0.3, 0.0, 150.0}.make(); // tan 20 = 0.36 < 1.75
  const double th = 20.0 * pi / 180;
  EXPECT_NEAR(acceleration(sim), 5.0 / 7.0 * std::sin(th), 1e-3 * std::sin(th));
  // Rolling: contact-point speed v - R w stays ~0.
  EXPECT_NEAR(sim.particles().v[0].x - sim.particles().w[0].y, 0.0, 1e-3);
}

TEST(Incline, SlidesAtGSinMinusMuDynamicCos) {
  Simulation sim = Incline{65.0, 0.5, 0.3}.make(); // tan 65 = 2.14 > 1.75
  const double th = 65.0 * pi / 180;
  const double expected = std::sin(th) - 0.3 * std::cos(th);
  EXPECT_NEAR(acceleration(sim), expected, 1e-3 * expected);
}

TEST(Incline, StaticDynamicBandRollsFromRest) {
  const double th = std::atan(1.4); // 3.5 mu_d = 1.05 < 1.4 < 3.5 mu_s = 1.75
  Simulation sim = Incline{th * 180 / pi, 0.5, 0.3, 0.0, 150.0}.make();
  EXPECT_NEAR(acceleration(sim), 5.0 / 7.0 * std::sin(th), 1e-3 * std::sin(th));
}

TEST(Incline, StaticDynamicBandKeepsSlidingWhenLaunchedWithSlip) {
  const double th = std::atan(1.4);
  Simulation sim = Incline{th * 180 / pi, 0.5, 0.3, 2.0}.make();
  const double expected = std::sin(th) - 0.3 * std::cos(th);
  EXPECT_NEAR(acceleration(sim), expected, 1e-3 * expected);
}

// MFiX DEM04 / validation.md L9: slip stops at t_s = 2 v0 / (7 mu_d g), then the sphere rolls
// at v_f = R w_f = (5/7) v0 whatever the friction history.
double slip_stop_time(Simulation& sim, double until) {
  double t_stop = -1;
  while (sim.time() < until) {
    sim.step();
    const double slip = sim.particles().v[0].x - sim.particles().w[0].y;
    if (t_stop < 0 && slip < 1e-6) t_stop = sim.time();
  }
  return t_stop;
}

TEST(Incline, SlipStopsAtTwoSeventhsOfV0OverMuG) {
  const double v0 = 1.0, mu_d = 0.3, t_s = 2 * v0 / (7 * mu_d);
  Simulation sim = Incline{0.0, 0.5, mu_d, v0}.make();
  EXPECT_NEAR(slip_stop_time(sim, 2 * t_s), t_s, 0.01 * t_s);
}

TEST(Incline, SlipToRollEndsAtFiveSeventhsOfTheLaunchSpeed) {
  const double v0 = 1.0, mu_d = 0.3, t_s = 2 * v0 / (7 * mu_d);
  Simulation sim = Incline{0.0, 0.5, mu_d, v0, 150.0}.make(); // damped spring after sticking
  slip_stop_time(sim, 3 * t_s);
  EXPECT_NEAR(sim.particles().v[0].x, 5.0 / 7.0 * v0, 1e-3 * v0);
  EXPECT_NEAR(sim.particles().w[0].y, 5.0 / 7.0 * v0, 1e-3 * v0);
}

} // namespace
} // namespace yuxi
