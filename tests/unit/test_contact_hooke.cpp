// The frictionless Hooke spring (contact/hooke.hpp): through the engine, an undamped head-on
// collision keeps the kinetic energy and lasts pi sqrt(m*/k_n); with the dashpot it rebounds
// with the damped oscillator's restitution; an oblique impact exerts no torque; and scenes name
// it as model = "hooke".
#include "contact/hooke.hpp"
#include "core/random.hpp"
#include "core/units.hpp"
#include "io/scene_error.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "test_support.hpp"
#include "validation/collision_probe.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <string>

namespace yuxi {
namespace {

constexpr double radius = 0.5, mass = 1.0, m_eff = 0.5 * mass, k_n = 1e4;

AnyContactLaw hooke_law(double gamma_n) {
  ContactLaw<Hooke> law{PairTable<Hooke::Coeffs>(1)};
  law.coeffs.set(0, 0, {k_n, gamma_n});
  return law;
}

// The undamped contact time pi sqrt(m*/k_n).
double undamped_contact_time() {
  return pi * std::sqrt(m_eff / k_n);
}

// Two grains approaching along x at relative speed 2, their centres `offset` apart in y (0:
// head-on), touching after about 100 steps.
Simulation two_grains(double gamma_n, double offset, double dt) {
  auto cfg = test::open_box(4.0, {0, 0, 0}, dt);
  const double gap = 2 * 100 * dt;
  const double dx = std::sqrt(4 * radius * radius - offset * offset) + gap;
  return Simulation(
      cfg,
      test::store_of({test::sphere({-0.5 * dx, 0.5 * offset, 0}, radius, mass, {1, 0, 0}),
                      test::sphere({0.5 * dx, -0.5 * offset, 0}, radius, mass, {-1, 0, 0})}),
      {}, {}, hooke_law(gamma_n));
}

TEST(HookeContact, UndampedHeadOnCollisionKeepsTheKineticEnergy) {
  const double t_c = undamped_contact_time();
  const double dt = t_c / 10000; // velocity Verlet: the error at the kinks falls like dt^3
  Simulation sim = two_grains(0.0, 0.0, dt);
  const double before = sim.energies().kinetic();
  const auto rec = test::collide(sim, 20000);
  const auto e = sim.energies();
  ASSERT_GT(rec.contact_time, 0.0);
  EXPECT_NEAR(e.kinetic(), before, 1e-9 * before);
  EXPECT_EQ(e.dissipated, 0.0);
  EXPECT_NEAR(rec.contact_time, t_c, dt);
  EXPECT_NEAR(rec.v_after.x, -rec.v_before.x, 1e-9);
}

// m* delta'' + m* gamma_n delta' + k_n delta = 0 has the damping ratio
// zeta = gamma_n / (2 sqrt(k_n/m*)) and restitution exp(-pi zeta / sqrt(1 - zeta^2)).
TEST(HookeContact, DampedRestitutionMatchesTheOscillator) {
  for (const double zeta : {0.05, 0.2, 0.5}) {
    SCOPED_TRACE(testing::Message() << "zeta = " << zeta);
    const double gamma_n = 2 * zeta * std::sqrt(k_n / m_eff);
    const double expected = std::exp(-pi * zeta / std::sqrt(1 - zeta * zeta));
    const double dt = Hooke::contact_time({k_n, gamma_n}, m_eff, 0.0, 0.0) / 2000;
    Simulation sim = two_grains(gamma_n, 0.0, dt);
    const double b0 = sim.energies().balance();
    const auto rec = test::collide(sim, 20000);
    ASSERT_GT(rec.contact_time, 0.0);
    const double e = -rec.v_after.x / rec.v_before.x;
    EXPECT_NEAR(e, expected, 1e-3 * expected);
    // The books close: what the grains lost is what the dashpot dissipated.
    const auto books = sim.energies();
    ASSERT_GT(books.dissipated, 0.0);
    EXPECT_LT(std::abs(books.balance() - b0), 1e-2 * books.dissipated);
  }
}

TEST(HookeContact, ObliqueImpactLeavesTheGrainsWithoutSpin) {
  const double dt = undamped_contact_time() / 2000;
  Simulation sim = two_grains(20.0, 0.6, dt);
  const auto rec = test::collide(sim, 20000);
  ASSERT_GT(rec.contact_time, 0.0);
  EXPECT_GT(std::abs(rec.v_after.y), 0.1); // deflected: the contact was oblique
  for (std::size_t i = 0; i < sim.particles().n_owned(); ++i) {
    EXPECT_EQ(sim.particles().w[i], Vec3{}) << "grain " << i;
  }
}

// Evaluated alone: a central force along n whatever the spins, the same seen from either side.
TEST(HookeContact, ForceIsCentralAndOpposite) {
  Random r(11);
  const Hooke::Coeffs c{k_n, 30.0};
  for (int k = 0; k < 100; ++k) {
    ContactGeometry g;
    const Vec3 n{r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
    g.n = n / norm(n);
    g.a_i = r.uniform(0.3, 0.6);
    g.a_j = r.uniform(0.3, 0.6);
    g.overlap = r.uniform(1e-4, 1e-2);
    g.distance = g.a_i + g.a_j - g.overlap;
    g.v_rel = {r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)};
    g.w_i = {r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)};
    g.w_j = {r.uniform(-5, 5), r.uniform(-5, 5), r.uniform(-5, 5)};
    g.m_eff = m_eff;
    g.r_eff = g.a_i * g.a_j / (g.a_i + g.a_j);
    g.dt = 1e-4;
    Hooke::State s;
    const ContactResult f = Hooke::evaluate(g, c, s);
    EXPECT_LT(norm(cross(f.force, g.n)), 1e-12 * norm(f.force));
    EXPECT_EQ(f.torque_i, Vec3{});
    EXPECT_EQ(f.torque_j, Vec3{});
    EXPECT_DOUBLE_EQ(f.elastic, 0.5 * k_n * g.overlap * g.overlap);

    ContactGeometry seen_from_j = g;
    seen_from_j.n = -g.n;
    seen_from_j.v_rel = -g.v_rel;
    std::swap(seen_from_j.w_i, seen_from_j.w_j);
    std::swap(seen_from_j.a_i, seen_from_j.a_j);
    Hooke::State mirrored = s.mirrored();
    const ContactResult b = Hooke::evaluate(seen_from_j, c, mirrored);
    EXPECT_EQ(b.force, -f.force);
    EXPECT_EQ(b.dissipated, f.dissipated);
  }
  Hooke::State s;
  EXPECT_EQ(Hooke::release(c, s), 0.0);
}

const char* const hooke_scene = R"(materials = ["grain", "wall"]

[run]
dt = 1.0e-4
t_end = 0.01

[domain]
lo = [0.0, 0.0, 0.0]
hi = [10.0, 10.0, 10.0]
boundary = ["periodic", "periodic", "wall"]
gravity = [0.0, 0.0, -1.0]
wall_material = "wall"

[contact]
model = "hooke"

[[contact.pair]]
materials = ["grain", "grain"]
k_n = 2.5e5
gamma_n = 100.0

[[contact.pair]]
materials = ["grain", "wall"]
k_n = 1.0e6

[[particle]]
position = [5.0, 5.0, 5.0]
radius = 1.0
mass = 1.0
material = "grain"
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// Reading `text` fails with a message that contains `expected`.
void expect_error(const std::string& text, const std::string& expected) {
  try {
    read_scene_text(text, "hooke.toml");
    ADD_FAILURE() << "accepted; expected: " << expected;
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

TEST(HookeScene, IsReadWithItsKeysAndDefaults) {
  const Scene s = read_scene_text(hooke_scene, "hooke.toml");
  EXPECT_EQ(s.contact_model, "hooke");
  const auto* law = std::get_if<ContactLaw<Hooke>>(&s.law);
  ASSERT_NE(law, nullptr);
  EXPECT_EQ(law->coeffs(0, 0).k_n, 2.5e5);
  EXPECT_EQ(law->coeffs(0, 0).gamma_n, 100.0);
  EXPECT_EQ(law->coeffs(0, 1).k_n, 1.0e6);
  EXPECT_EQ(law->coeffs(1, 0).gamma_n, 0.0); // optional: no dashpot
  // The resolved scene reads back to the same coefficients.
  const Scene again = read_scene_text(resolved_scene_toml(s), "resolved.toml");
  const auto* law_again = std::get_if<ContactLaw<Hooke>>(&again.law);
  ASSERT_NE(law_again, nullptr);
  EXPECT_EQ(law_again->coeffs(0, 0).gamma_n, 100.0);
  EXPECT_EQ(law_again->coeffs(0, 1).k_n, 1.0e6);
}

TEST(HookeScene, MistakesNameTheKey) {
  expect_error(replaced(hooke_scene, "k_n = 1.0e6", "gamma_n = 1.0"), "missing key 'k_n'");
  expect_error(replaced(hooke_scene, "gamma_n = 100.0", "gamma_n = -1.0"),
               "contact.pair[1].gamma_n");
  // Frictionless: the linear model's friction keys are not the Hooke spring's.
  expect_error(replaced(hooke_scene, "gamma_n = 100.0", "mu_s = 0.5"),
               "contact.pair[1].mu_s: unknown key");
  expect_error(replaced(hooke_scene, "model = \"hooke\"", "model = \"hooke\"\npreset = \"lammps\""),
               "the lammps preset applies to the linear model only");
}

} // namespace
} // namespace yuxi
