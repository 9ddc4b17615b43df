#include "contact/thermodynamic.hpp"

#include "contact/example_units.hpp"
#include "contact/frictional_spring.hpp"
#include "contact/hertz_mindlin.hpp"

#include <algorithm>
#include <cmath>

namespace yuxi {
namespace {

// u rotated by the rotation that takes the unit vector `from` to the unit vector `to` about
// their common normal (Rodrigues, with a = from x to, c = from . to):
// u' = c u + a x u + a (a . u) / (1 + c).
Vec3 rotate_minimal(const Vec3& u, const Vec3& from, const Vec3& to) {
  const double c = dot(from, to);
  if (c <= -1.0 + 1e-12) return -u; // the normal turned over in one step: no unique rotation
  const Vec3 a = cross(from, to);
  return c * u + cross(a, u) + a * (dot(a, u) / (1 + c));
}

} // namespace

thermo::ExampleModel Thermodynamic::Coeffs::model() const {
  thermo::ExampleModel m;
  m.xi = thermo::xi_of_friction(friction);
  m.gear = gear;
  m.eta_hat = eta_hat;
  m.eta_power = eta_power;
  m.lambda_hat = lambda_hat;
  m.tau_hat = tau_hat;
  m.epsilon = 0;
  m.viscosity_to_heat = viscosity_to == ViscosityChannel::heat;
  return m;
}

Thermodynamic::Coeffs Thermodynamic::with_materials(const Coeffs& c, double youngs_1,
                                                    double poisson_1, double youngs_2,
                                                    double poisson_2) {
  Coeffs out = c;
  out.e_star = HertzMindlin::mix(youngs_1, poisson_1, youngs_2, poisson_2, 1.0, 0.0).e_star;
  return out;
}

Thermodynamic::Coeffs Thermodynamic::example() {
  Coeffs c;
  c.e_star = example_units::e_star;
  return c;
}

thermo::ExampleCoefficients Thermodynamic::coefficients(const Coeffs& c, double m_eff, double r_eff,
                                                        double d) {
  const double k = spring_constant(c, r_eff);
  return thermo::ExampleCoefficients::of(c.model(), k, m_eff, d);
}

double Thermodynamic::contact_time(const Coeffs& c, double m_eff, double r_eff, double v) {
  const double k = spring_constant(c, r_eff) * std::pow(c.gear, 2.5);
  const double t_normal = 2.9432 * std::pow(5 * m_eff / (4 * k), 0.4) * std::pow(v, -0.2);
  // The tangential spring is k_t/k_n = 4/(3 xi) times stiffer than the normal one (spec 4) and
  // acts on 2/7 of the mass for rolling spheres: its half period is shorter when that exceeds 1.
  const double ratio = 4.0 / (3.0 * thermo::xi_of_friction(c.friction)) * 3.5;
  return t_normal / std::sqrt(std::max(1.0, ratio));
}

ContactResult Thermodynamic::evaluate(const ContactGeometry& g, const Coeffs& c, State& s) {
  ContactResult r;
  r.touching = true;
  const double delta = g.overlap;
  const bool flat_wall = g.a_j == 0.0;
  const double d = flat_wall ? 2 * g.a_i : g.a_i + g.a_j;
  const thermo::ExampleCoefficients co = coefficients(c, g.m_eff, g.r_eff, d);
  const double k = co.k, xi = co.xi, dt = g.dt;

  // Branch lengths (spec 2.2): the contact point sits delta/2 inside each sphere (at the plane
  // of a flat wall).
  ContactGeometry b = g;
  b.a_i = flat_wall ? g.a_i - delta : g.a_i - 0.5 * delta;
  b.a_j = flat_wall ? 0.0 : g.a_j - 0.5 * delta;
  const auto [vn, vt] = split_contact_velocity(b);

  // a. carry the tangential spring into the current tangent plane.
  Vec3 ut = s.ut;
  if (norm2(s.n_prev) > 0) ut = carry_in_plane(rotate_minimal(ut, s.n_prev, g.n), g.n);
  // b. gearbox, (30)-(31) with lambda_n = 0: exact primitive for u_n, midpoint G for u_t.
  double un = s.un - co.gear * (thermo::heaviside_primitive(delta, d, co.epsilon) -
                                thermo::heaviside_primitive(s.delta_prev, d, co.epsilon));
  un = std::min(un, 0.0);
  ut += co.gearbox(0.5 * (delta + s.delta_prev)) * dt * vt;
  const double w_before = thermo::elastic_energy(k, xi, un, norm2(ut));
  // c. tangential relaxation (40), exact for fixed u_n.
  const double kappa = thermo::tangential_stiffness(k, xi, un);
  ut *= std::exp(-co.relaxation_rate(s.w_relax) * kappa * dt);
  // d. yield (41): back onto the stability boundary (35).
  const double limit = thermo::yield_limit(xi, un);
  const double ut_len = norm(ut);
  if (ut_len > limit) ut *= ut_len > 0 ? limit / ut_len : 0.0;
  const double w_el = thermo::elastic_energy(k, xi, un, norm2(ut));
  double heat = w_before - w_el;
  // e. w_R decays into heat (22).
  double w_relax = s.w_relax * std::exp(-dt / co.tau);
  heat += s.w_relax - w_relax;

  // Force (28)-(29) and the viscous power of (32)/(33).
  const double gear = co.gearbox(delta);
  const double eta = co.viscosity(delta);
  const double pi_n = thermo::normal_spring_force(k, xi, un, norm2(ut));
  const Vec3 pi_t = -kappa * ut;
  r.add_contact_force(b, gear * pi_n - eta * vn, gear * pi_t - eta * vt);
  const Vec3 vc = vn * g.n + vt;
  const double viscous = eta * norm2(vc) * dt;
  const double booked = dot(s.owed, vc) + 0.5 * viscous;
  s.owed = 0.5 * eta * dt * vc;
  s.owed_energy = 0.5 * viscous;
  if (co.viscosity_to_heat)
    heat += booked;
  else
    w_relax += booked;

  s.un = un;
  s.ut = ut;
  s.w_relax = w_relax;
  s.stored = w_el;
  s.n_prev = g.n;
  s.delta_prev = delta;
  r.elastic = w_el;
  r.relaxation = w_relax;
  r.dissipated = heat;
  return r;
}

double Thermodynamic::release(const Coeffs&, State& s) {
  const double e = s.stored + s.w_relax + s.owed_energy;
  s = State{};
  return e;
}

} // namespace yuxi
