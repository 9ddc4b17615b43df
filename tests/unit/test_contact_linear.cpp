// The linear spring-dashpot law on its own: Newton's third law, objectivity under rotation,
// and the static/dynamic friction switch (docs/models/fish-basin.md section 5).
#include "contact/linear_spring_dashpot.hpp"
#include "core/random.hpp"

#include <gtest/gtest.h>

namespace yuxi {
namespace {

using Law = LinearSpringDashpot;

Law::Coeffs paper_grain_grain() {
  return {2.5e5, 0.57e5, 100.0, 32.0, 0.84, 0.4};
}

Vec3 random_vec(Random& r, double scale) {
  return {r.uniform(-scale, scale), r.uniform(-scale, scale), r.uniform(-scale, scale)};
}

ContactGeometry random_geometry(Random& r) {
  ContactGeometry g;
  Vec3 n = random_vec(r, 1.0);
  g.n = n / norm(n);
  g.a_i = r.uniform(0.7, 1.3);
  g.a_j = r.uniform(0.7, 1.3);
  g.overlap = r.uniform(1e-4, 2e-2);
  g.distance = g.a_i + g.a_j - g.overlap;
  g.v_rel = random_vec(r, 2.0);
  g.w_i = random_vec(r, 3.0);
  g.w_j = random_vec(r, 3.0);
  g.m_eff = 0.4;
  g.r_eff = g.a_i * g.a_j / (g.a_i + g.a_j);
  g.dt = 1e-4;
  return g;
}

// The same contact described from j's side.
ContactGeometry swapped(const ContactGeometry& g) {
  ContactGeometry s = g;
  s.n = -g.n;
  s.v_rel = -g.v_rel;
  std::swap(s.w_i, s.w_j);
  std::swap(s.a_i, s.a_j);
  return s;
}

// A contact state whose tangential spring holds s (in the plane normal to n).
Law::State with_spring(Vec3 s, const Vec3& n, const Law::Coeffs& c) {
  Law::State st;
  st.tangential.spring = s - dot(s, n) * n;
  st.tangential.k = c.k_t;
  return st;
}

void expect_near(const Vec3& a, const Vec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(LinearContact, NewtonsThirdLawWithHistory) {
  Random r(3);
  for (int k = 0; k < 200; ++k) {
    const ContactGeometry g = random_geometry(r);
    Law::State s_ij = with_spring(random_vec(r, 1e-3), g.n, paper_grain_grain());
    Law::State s_ji = s_ij.mirrored();
    const auto f_ij = Law::evaluate(g, paper_grain_grain(), s_ij);
    const auto f_ji = Law::evaluate(swapped(g), paper_grain_grain(), s_ji);
    expect_near(f_ji.force, -f_ij.force, 1e-9 * norm(f_ij.force));
    expect_near(f_ji.torque_i, f_ij.torque_j, 1e-9 * norm(f_ij.force));
    expect_near(f_ji.torque_j, f_ij.torque_i, 1e-9 * norm(f_ij.force));
    expect_near(s_ji.tangential.spring, -s_ij.tangential.spring, 1e-15);
    EXPECT_NEAR(f_ij.elastic, f_ji.elastic, 1e-12 * f_ij.elastic);
  }
}

// Rotation about a random axis by Rodrigues' formula.
struct Rotation {
  Vec3 axis;
  double angle;
  Vec3 operator()(const Vec3& v) const {
    const double c = std::cos(angle), s = std::sin(angle);
    return c * v + s * cross(axis, v) + (1 - c) * dot(axis, v) * axis;
  }
};

TEST(LinearContact, ForceRotatesWithTheFrame) {
  Random r(4);
  for (int k = 0; k < 200; ++k) {
    ContactGeometry g = random_geometry(r);
    Vec3 axis = random_vec(r, 1.0);
    const Rotation rot{axis / norm(axis), r.uniform(0, 6.28)};
    Law::State s = with_spring(random_vec(r, 1e-3), g.n, paper_grain_grain());
    ContactGeometry gr = g;
    gr.n = rot(g.n);
    gr.v_rel = rot(g.v_rel);
    gr.w_i = rot(g.w_i);
    gr.w_j = rot(g.w_j);
    Law::State sr = s;
    sr.tangential.spring = rot(s.tangential.spring);
    const auto f = Law::evaluate(g, paper_grain_grain(), s);
    const auto fr = Law::evaluate(gr, paper_grain_grain(), sr);
    const double tol = 1e-9 * norm(f.force);
    expect_near(fr.force, rot(f.force), tol);
    expect_near(fr.torque_i, rot(f.torque_i), tol);
    expect_near(sr.tangential.spring, rot(s.tangential.spring), 1e-15);
  }
}

TEST(LinearContact, SticksBelowMuStaticThenSlidesAtMuDynamic) {
  // Fixed overlap, steady tangential slip: the spring loads until mu_s |F_n|, then the force
  // drops to mu_d |F_n| and stays there while the slip goes on.
  Law::Coeffs c{1e5, 2e4, 0.0, 0.0, 0.8, 0.4};
  ContactGeometry g;
  g.n = {0, 0, 1};
  g.overlap = 1e-3;
  g.a_i = 1.0;
  g.a_j = 1.0;
  g.distance = 2.0 - g.overlap;
  g.v_rel = {1.0, 0, 0};
  g.m_eff = 0.5;
  g.dt = 1e-4;
  const double fn = c.k_n * g.overlap; // 100
  Law::State s;
  double peak = 0;
  int first_slide = -1;
  for (int k = 0; k < 400; ++k) {
    const auto r = Law::evaluate(g, c, s);
    const double ft = std::hypot(r.force.x, r.force.y);
    if (s.tangential.sliding && first_slide < 0) first_slide = k;
    if (first_slide < 0) {
      EXPECT_NEAR(ft, c.k_t * g.dt * (k + 1), 1e-9); // linear loading of the spring
      peak = std::max(peak, ft);
    } else {
      EXPECT_NEAR(ft, c.mu_d * fn, 1e-9);
      EXPECT_TRUE(s.tangential.sliding);
    }
  }
  ASSERT_GT(first_slide, 0);
  EXPECT_LE(peak, c.mu_s * fn + 1e-9);
  EXPECT_GT(peak, c.mu_s * fn - c.k_t * g.dt * 1.0001);
  // Reversing the slip unloads the spring below mu_d: the contact sticks again.
  g.v_rel = {-1.0, 0, 0};
  Law::evaluate(g, c, s);
  EXPECT_FALSE(s.tangential.sliding);
}

TEST(LinearContact, OpeningContactForgetsItsSpringAndLosesItsEnergy) {
  Law::State s;
  s.tangential = {.spring = {1e-3, 0, 0}, .sliding = 1, .k = paper_grain_grain().k_t};
  const double lost = Law::release(paper_grain_grain(), s);
  EXPECT_EQ(s, Law::State{});
  EXPECT_DOUBLE_EQ(lost, 0.5 * paper_grain_grain().k_t * 1e-6);
}

TEST(LinearContact, ContactTimeFormula) {
  // docs/models/validation.md L1, Silbert et al. 2001 units: t_c = 4.97118e-3.
  Law::Coeffs c{2e5, 0, 50.0, 0, 0, 0};
  EXPECT_NEAR(Law::contact_time(c, 0.5, 0.5, 1.0), 4.97118e-3, 1e-8);
}

} // namespace
} // namespace yuxi
