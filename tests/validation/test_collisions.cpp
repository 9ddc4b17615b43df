// Binary collisions against closed forms (validation.md L1, L6, L7).
#include "core/units.hpp"
#include "validation/collision_probe.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

using test::Coeffs;

// L1: head-on, no gravity, no friction: e = exp(-gamma_n t_c / 2), t_c = pi / omega with
// omega = sqrt(k_n / m_eff - gamma_n^2 / 4). The partner is a second grain (m_eff = m/2), a
// wall particle or a flat wall (m_eff = m).
enum class Partner { grain, wall_particle, plane };

class HeadOn : public ::testing::TestWithParam<Partner> {};

TEST_P(HeadOn, RestitutionAndContactTimeMatchTheory) {
  const Partner partner = GetParam();
  const double k_n = 2e5, gamma_n = 50.0, m = 1.0, r = 0.5, v0 = 1.0;
  const double m_eff = partner == Partner::grain ? 0.5 * m : m;
  const double omega = std::sqrt(k_n / m_eff - 0.25 * gamma_n * gamma_n);
  const double t_c = pi / omega;
  const double e = std::exp(-0.5 * gamma_n * t_c);
  const double dt = t_c / 1000;

  auto cfg = test::open_box(5.0, {}, dt);
  std::vector<ParticleSpec> specs{test::sphere({0, 0, r + 1e-6}, r, m, {0, 0, -v0})};
  std::vector<PlaneWall> planes;
  if (partner == Partner::grain) specs.push_back(test::sphere({0, 0, -r - 1e-6}, r, m, {0, 0, v0}));
  if (partner == Partner::wall_particle) {
    auto w = test::sphere({0, 0, -r - 1e-6}, r, m);
    w.kind = Kind::wall;
    specs.push_back(w);
  }
  if (partner == Partner::plane) planes.push_back(test::plane({0, 0, 0}, {0, 0, 1}));
  Simulation sim(cfg, test::store_of(specs), planes, {},
                 test::linear_law({k_n, 0, gamma_n, 0, 0, 0}));
  const auto rec = test::collide(sim, 5000);

  // Relative approach speed: 2 v0 against a moving grain, v0 against a fixed partner.
  const double measured_e = rec.v_after.z / v0;
  EXPECT_NEAR(measured_e, e, 0.005 * e);
  EXPECT_NEAR(rec.contact_time, t_c, 0.005 * t_c);
  EXPECT_NEAR(rec.v_after.x, 0.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Partners, HeadOn,
                         ::testing::Values(Partner::grain, Partner::wall_particle, Partner::plane),
                         [](const ::testing::TestParamInfo<Partner>& p) {
                           return p.param == Partner::grain           ? std::string("grain")
                                  : p.param == Partner::wall_particle ? std::string("wall_particle")
                                                                      : std::string("plane");
                         });

TEST(HeadOn, SilbertUnitsGiveThePublishedNumbers) {
  // validation.md L1 table: k_n = 2e5, m_eff = 0.5, gamma_n = 50 -> t_c = 4.97118e-3, e = 0.883133.
  const double dt = 4.97118e-3 / 1000;
  auto cfg = test::open_box(5.0, {}, dt);
  Simulation sim(cfg,
                 test::store_of({test::sphere({0, 0, 0.5}, 0.5, 1.0, {0, 0, -0.5}),
                                 test::sphere({0, 0, -0.5}, 0.5, 1.0, {0, 0, 0.5})}),
                 {}, {}, test::linear_law({2e5, 0, 50.0, 0, 0, 0}));
  const auto rec = test::collide(sim, 5000);
  EXPECT_NEAR(rec.v_after.z / 0.5, 0.883133, 0.005 * 0.883133);
  EXPECT_NEAR(rec.contact_time, 4.97118e-3, 0.005 * 4.97118e-3);
}

// Impact of a sphere on a flat wall at angle theta from the normal, speed V, no spin.
test::CollisionRecord oblique(const Coeffs& c, double theta_deg, double dt) {
  const double r = 1.0, m = 1.0, v = 1.0, th = theta_deg * pi / 180;
  auto cfg = test::open_box(10.0, {}, dt);
  Simulation sim(
      cfg,
      test::store_of({test::sphere({0, 0, r}, r, m, {v * std::sin(th), 0, -v * std::cos(th)})}),
      {test::plane({0, 0, 0}, {0, 0, 1})}, {}, test::linear_law(c));
  return test::collide(sim, 100000);
}

// L6: k_t = (2/7) k_n, no damping, full stick: e_n = 1, e_t = 3/7, beta = 1, R w' = (10/7) v_t0.
class ObliqueStick : public ::testing::TestWithParam<double> {};

TEST_P(ObliqueStick, TangentialRestitutionIsThreeSevenths) {
  const double theta = GetParam(), k_n = 1e5;
  const double t_c = pi / std::sqrt(k_n);
  const auto rec = oblique({k_n, 2.0 / 7.0 * k_n, 0, 0, 1e6, 1e6}, theta, t_c / 400);
  const double vt0 = std::sin(theta * pi / 180), vn0 = std::cos(theta * pi / 180);
  EXPECT_NEAR(rec.v_after.z / vn0, 1.0, 1e-3);
  EXPECT_NEAR(rec.v_after.x / vt0, 3.0 / 7.0, 1e-3);
  EXPECT_NEAR(rec.w_after.y / vt0, 10.0 / 7.0, 1e-3); // R = 1, rolling forward
  const double u0 = vt0, u1 = rec.v_after.x - rec.w_after.y;
  EXPECT_NEAR(-u1 / u0, 1.0, 2e-3); // beta
}

INSTANTIATE_TEST_SUITE_P(Angles, ObliqueStick, ::testing::Values(10.0, 30.0, 45.0));

// L7: gross sliding through the whole impact: e_t = 1 - mu (1 + e) / tan(theta),
// |w'| R = (5/2) mu (1 + e) V cos(theta).
class ObliqueSliding : public ::testing::TestWithParam<double> {};

TEST_P(ObliqueSliding, TangentialRestitutionFollowsCoulomb) {
  const double theta = GetParam(), k_n = 1e5, e = 0.98, mu = 0.092;
  // gamma_n from e for m_eff = m = 1: gamma_n = 2 omega0 |ln e| / sqrt(pi^2 + ln^2 e)
  const double le = std::log(e), gamma_n = 2 * std::sqrt(k_n) * -le / std::sqrt(pi * pi + le * le);
  const double t_c = pi / std::sqrt(k_n);
  const auto rec = oblique({k_n, 2.0 / 7.0 * k_n, gamma_n, 0, mu, mu}, theta, t_c / 400);
  const double th = theta * pi / 180;
  const double expected_et = 1 - mu * (1 + e) / std::tan(th);
  EXPECT_NEAR(rec.v_after.x / std::sin(th), expected_et, 0.005 * expected_et);
  EXPECT_NEAR(std::abs(rec.w_after.y), 2.5 * mu * (1 + e) * std::cos(th),
              0.005 * 2.5 * mu * (1 + e) * std::cos(th));
}

INSTANTIATE_TEST_SUITE_P(Angles, ObliqueSliding, ::testing::Values(60.0, 75.0));

TEST(Collision, TwoGrainsConserveMomentum) {
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
