// Rigid clumps of spheres against rigid-body mechanics (docs/clumps.md): a dumbbell rolls down
// an incline at g sin(theta) / (1 + I / (M r^2)), a dumbbell dropped flat bounces as two
// spring-dashpots in parallel on its whole mass, a tilted one as a single impact whose
// effective mass includes its turning, 1 / (1/M + (b x n) . I^-1 (b x n)).
#include "core/units.hpp"
#include "test_support.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

constexpr double unit_density = 3.0 / (4.0 * pi); // a sphere of radius 1 weighs 1

// Two spheres of radius r whose centres are `gap` apart, along the principal axis of the
// smallest moment (the body's x).
ClumpShape dumbbell(double r, double gap) {
  return make_clump_shape("dumbbell",
                          std::vector<SphereMember>{{{-gap / 2, 0, 0}, r}, {{gap / 2, 0, 0}, r}});
}

struct OneClump {
  ParticleStore store;
  std::vector<ClumpBody> bodies;
};

OneClump one_clump(const ClumpShape& shape, const Vec3& x, const Quaternion& q, const Vec3& v) {
  OneClump out;
  const PlacedClump c = make_clump(shape, unit_density, 0, 0, x, q, v);
  for (std::size_t k = 0; k < c.members.size(); ++k)
    out.store.add(c.members[k], c.body.id + static_cast<GlobalId>(k));
  out.bodies.push_back(c.body);
  return out;
}

// A dumbbell (axis across the slope) on a plane, gravity tilted by theta: both spheres roll
// without slipping about the axis, the clump's smallest principal moment I1, so the centre
// accelerates at g sin(theta) / (1 + I1 / (M r^2)), and the clump turns at v / r. Touching
// spheres give a sphere's 5/7; overlapping ones a smaller moment, so a larger acceleration.
class DumbbellOnIncline : public ::testing::TestWithParam<double> {};

TEST_P(DumbbellOnIncline, RollsAtTheRigidBodysAcceleration) {
  const double r = 1.0, gap = GetParam() * r, theta = 20.0 * pi / 180.0, g = 1.0;
  const ClumpShape shape = dumbbell(r, gap);
  test::Coeffs c{1e5, 2.0 / 7.0 * 1e5, 30.0, 150.0, 0.8, 0.8};
  auto cfg = test::open_box(40, {g * std::sin(theta), 0, -g * std::cos(theta)},
                            0.02 * pi / std::sqrt(1e5));
  // The body's x (the dumbbell's axis) along the lab's y.
  const Quaternion q = about_axis({0, 0, 1}, pi / 2);
  OneClump scene = one_clump(shape, {-20, 0, r - 1e-5}, q, {});
  Simulation sim(cfg, std::move(scene.store), {test::plane({0, 0, 0}, {0, 0, 1})}, {},
                 test::linear_law(c), Comm::world(), {}, std::move(scene.bodies));
  for (std::size_t i = 0; i < 2; ++i) { // both members on the floor, across the slope
    EXPECT_NEAR(std::abs(sim.particles().x[i].y), gap / 2, 1e-12);
    EXPECT_NEAR(sim.particles().x[i].z, r - 1e-5, 1e-12);
  }
  const double b0 = sim.energies().balance();
  sim.run(std::llround(2.0 / cfg.dt));
  const double v1 = sim.clumps()[0].v.x, t1 = sim.time();
  sim.run(std::llround(4.0 / cfg.dt));
  const ClumpBody& body = sim.clumps()[0];
  const double a = (body.v.x - v1) / (sim.time() - t1);
  const double mass = body.mass, axial = body.inertia.x;
  const double expected = g * std::sin(theta) / (1.0 + axial / (mass * r * r));
  EXPECT_NEAR(a, expected, 1e-6 * expected); // (1e-12 when written)
  if (gap >= 2 * r) {
    EXPECT_NEAR(expected, 5.0 / 7.0 * g * std::sin(theta), 1e-12);
  }
  const Vec3 omega = body.angular_velocity();
  EXPECT_NEAR(body.v.x - r * omega.y, 0.0, 1e-3 * body.v.x); // rolling, not sliding
  EXPECT_NEAR(omega.x, 0.0, 1e-6);
  EXPECT_NEAR(omega.z, 0.0, 1e-6);
  EXPECT_NEAR(body.v.y, 0.0, 1e-9);
  // The books close: what the friction spring dissipates is what the rolling clump lost.
  const EnergyBooks e = sim.energies();
  EXPECT_LT(std::abs(e.balance() - b0), 1e-4 * std::abs(e.gravitational));
}

INSTANTIATE_TEST_SUITE_P(Gaps, DumbbellOnIncline, ::testing::Values(2.0, 1.2),
                         [](const ::testing::TestParamInfo<double>& p) {
                           return p.param >= 2.0 ? std::string("touching")
                                                 : std::string("overlapping");
                         });

// Frictionless linear spring-dashpots: F = k delta - m_e gamma v_n, where m_e is the clump's
// mass M (the mass its members take in contacts).
AnyContactLaw frictionless(double k, double gamma) {
  return test::linear_law({k, 0.0, gamma, 0.0, 0.0, 0.0});
}

// Runs from the first contact to its end (no contact left); returns false if none was made.
bool bounce(Simulation& sim, double t_max) {
  bool touched = false;
  while (sim.time() < t_max) {
    sim.step();
    const bool touching = sim.last_tally().touching > 0;
    if (touched && !touching) return true;
    touched = touched || touching;
  }
  return false;
}

// Dropped flat, both spheres meet the plane at once: M delta'' = -2 k delta - 2 M gamma delta',
// so the clump leaves at e v0 with e = exp(-gamma t_c), t_c = pi / sqrt(2 k / M - gamma^2),
// and does not turn.
TEST(ClumpImpact, DroppedFlatItBouncesAsTwoContactsInParallel) {
  const double r = 1.0, k = 1e5, gamma = 40.0, v0 = 1.0;
  const ClumpShape shape = dumbbell(r, 1.5 * r);
  auto cfg = test::open_box(10, {0, 0, 0}, 1e-5);
  OneClump scene = one_clump(shape, {0, 0, r + 1e-3}, Quaternion{}, {0, 0, -v0});
  Simulation sim(cfg, std::move(scene.store), {test::plane({0, 0, 0}, {0, 0, 1})}, {},
                 frictionless(k, gamma), Comm::world(), {}, std::move(scene.bodies));
  const double b0 = sim.energies().balance();
  ASSERT_TRUE(bounce(sim, 1.0));
  const ClumpBody& body = sim.clumps()[0];
  const double t_c = pi / std::sqrt(2.0 * k / body.mass - gamma * gamma);
  const double e = std::exp(-gamma * t_c);
  EXPECT_NEAR(body.v.z, e * v0, 2e-3 * e * v0);
  EXPECT_LT(norm(body.angular_velocity()), 1e-12);
  EXPECT_NEAR(body.v.x, 0.0, 1e-12);
  // What the clump lost went into the dashpots (the books' error is first order in dt / t_c:
  // the dashpot's force jumps where the contact begins).
  const EnergyBooks books = sim.energies();
  EXPECT_NEAR(books.dissipated, 0.5 * body.mass * v0 * v0 * (1 - e * e), 1e-2 * books.dissipated);
  EXPECT_LT(std::abs(books.balance() - b0), 2e-3 * books.dissipated);
}

// Tilted by alpha, one sphere meets the plane first: at that point the clump responds with
// the effective mass m* = 1 / (1/M + (b x n) . I^-1 (b x n)), b the member's arm, and the law's
// dashpot acts with M: m* u'' = -k u - M gamma u'. The contact ends at u' = -e v0 with
// e = exp(-beta t_c), beta = M gamma / (2 m*), t_c = pi / sqrt(k / m* - beta^2); the impulse
// J = m* (1 + e) v0 moves the centre by J / M and turns the clump by I^-1 (b x J n). (The
// clump turns a little during the contact, which a stiff contact keeps small.)
TEST(ClumpImpact, DroppedTiltedItBouncesAsARigidBodyImpact) {
  const double r = 1.0, k = 1e6, gamma = 100.0, v0 = 1.0, alpha = 30.0 * pi / 180.0;
  const ClumpShape shape = dumbbell(r, 1.5 * r);
  const Quaternion q = about_axis({0, 1, 0}, alpha);
  // The lower member's arm, and the height that sets it just above the plane.
  Vec3 low = to_lab(q, shape.members[0].centre);
  if (to_lab(q, shape.members[1].centre).z < low.z) low = to_lab(q, shape.members[1].centre);
  auto cfg = test::open_box(10, {0, 0, 0}, 2e-6);
  OneClump scene = one_clump(shape, {0, 0, r - low.z + 1e-4}, q, {0, 0, -v0});
  Simulation sim(cfg, std::move(scene.store), {test::plane({0, 0, 0}, {0, 0, 1})}, {},
                 frictionless(k, gamma), Comm::world(), {}, std::move(scene.bodies));
  const double b0 = sim.energies().balance();
  ASSERT_TRUE(bounce(sim, 0.1));
  const ClumpBody& body = sim.clumps()[0];
  const double mass = body.mass, across = body.inertia.y; // (= inertia.z: a dumbbell)
  const Vec3 n{0, 0, 1}, lever = cross(low, n);
  const double m_star = 1.0 / (1.0 / mass + dot(lever, lever) / across);
  const double beta = mass * gamma / (2.0 * m_star);
  const double t_c = pi / std::sqrt(k / m_star - beta * beta);
  const double e = std::exp(-beta * t_c), impulse = m_star * (1.0 + e) * v0;
  const Vec3 v = {0, 0, -v0 + impulse / mass};
  const Vec3 omega = (impulse / across) * lever;
  EXPECT_NEAR(body.v.z, v.z, 3e-3 * std::abs(v.z)); // (-9.6e-4 when written)
  EXPECT_NEAR(body.angular_velocity().y, omega.y, 1e-3 * std::abs(omega.y)); // (1.9e-5)
  EXPECT_NEAR(body.angular_velocity().x, 0.0, 1e-9);
  EXPECT_NEAR(body.angular_velocity().z, 0.0, 1e-9);
  // The rigid body kept its linear and angular momentum apart from the impulse: the centre's
  // sideways velocity stays zero (a frictionless plane pushes along n only).
  EXPECT_NEAR(body.v.x, 0.0, 1e-9);
  const EnergyBooks books = sim.energies();
  EXPECT_LT(std::abs(books.balance() - b0), 2e-3 * books.dissipated);
}

} // namespace
} // namespace yuxi
