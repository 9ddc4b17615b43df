// The thermodynamic contact model of Jiang & Liu (2018) in the DEM engine, 3-D with rotation:
// docs/models/thermodynamic-contact.md sections 2.2, 3, 4 and 7. A reconstruction: the paper's
// equations are lost; the formulas carry the spec's labels (thermodynamic_law.hpp), and the default
// parameter set is the spec's REF, not the paper's numbers.
//
// Per contact the state holds the springs' own deformations u_n <= 0 and u_t (a vector in the
// tangent plane), the relaxation energy w_R, and the normal and overlap of the previous step.
// One step (spec section 7, step 3), at the half-step velocities of velocity Verlet:
//   a. carry u_t from the previous tangent plane to the new one by the minimal rotation
//      (energy neutral, objective under rigid rotation);
//   b. gearbox (30)-(31): u_n -= gear (Phi(delta) - Phi(delta_prev)), u_t += G(delta_mid) v_t dt;
//   c. relaxation (40): u_t *= exp(-lambda_t kappa dt), lambda_t = Lambda sqrt(w_R), exact for
//      fixed u_n, kappa = (2k/xi)(-u_n)^{1/2};
//   d. yield (41) by return mapping: |u_t| <= sqrt(2 xi)(-u_n); c and d release elastic energy
//      into heat;
//   e. w_R decays exactly, w_R *= exp(-dt/tau), into heat (22);
// then the force (28)-(29): f_n = G pi_n - eta v_n, f_t = G pi_t - eta v_t, and the viscous
// power eta (v_n^2 + |v_t|^2) fills w_R (the relaxation channel of (39); heat if so chosen).
// Velocities are the half-step ones of velocity Verlet, which also drive the springs. The
// viscous force of a step acts in two half kicks (spec 7, steps 1 and 5): half its energy is
// booked at once, eta v^2 dt/2, the other half at the next step as (eta v dt/2) . v_next, the
// power of the same force at the velocity it then acts on. The books then close to second
// order in dt (the spec reaches the same with predicted velocities, which would make the
// springs move with velocities other than the displacement's).
// Lever arms are Luding's branch lengths a' = a - delta/2 (spec 2.2), so a rigid rotation of
// the pair moves no spring (test T11).
//
// The Heaviside step is sharp in the DEM engine: a contact is created at touching with
// u_n = u_t = w_R = 0 and, when it opens, the elastic and relaxation energy it still holds goes
// to heat (spec section 7, "contact life cycle"), so the energy books stay exact. The smoothed
// step is available in the two-grain solver.
//
// Spring constant: k = (4/3) E* sqrt(R*) per contact, so the model is Hertz at u_t = 0 (T1).
// One xi fixes both the friction mu = sqrt(2/xi) and k_t/k_n = 4/(3 xi) (spec 4).
#pragma once

#include "contact/contact_geometry.hpp"
#include "contact/frictional_spring.hpp"
#include "contact/thermodynamic_law.hpp"
#include "core/always_inline.hpp"
#include "core/host_device.hpp"
#include "core/portable_math.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string_view>

namespace yuxi {

enum class ViscosityChannel : std::uint8_t { relaxation, heat };

struct Thermodynamic {
  static constexpr std::string_view name = "thermodynamic";
  // Its contacts hold energy in a relaxation buffer (ContactResult::relaxation); the other laws'
  // is always zero, and the device engine keeps no room for it.
  static constexpr bool holds_relaxation = true;

  struct Coeffs {
    double e_star = 0;      // E* of the pair (as for Hertz-Mindlin) [force/length^2]
    double friction = 0.5;  // mu = sqrt(2/xi) (36) [-]
    double gear = 1;        // G inside the contact (38) [-]
    double eta_hat = 0.3;   // viscosity (39), in units of sqrt(m k d^{1/2}) [-]
    double eta_power = 0.5; // overlap exponent of the viscosity (39) [-]
    double lambda_hat = 10; // tangential relaxation by w_R (40) [-]
    double tau_hat = 5;     // decay time of w_R in units of t0 (22) [-]
    ViscosityChannel viscosity_to = ViscosityChannel::relaxation;

    YUXI_HD thermo::ExampleModel model() const {
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
  };

  struct State {
    double un = 0;          // normal spring deformation u_n <= 0 [length]
    Vec3 ut;                // tangential spring deformation, in the tangent plane [length]
    double w_relax = 0;     // relaxation energy w_R >= 0 [energy]
    double stored = 0;      // elastic energy w_el(u_n, u_t) after the last step [energy]
    Vec3 n_prev;            // normal at the last step (zero: a new contact)
    double delta_prev = 0;  // overlap at the last step [length]
    Vec3 owed;              // eta v_c dt/2 of the last step: its dot with this step's v_c is the
                            // second half of the last step's viscous energy [momentum]
    double owed_energy = 0; // eta |v_c|^2 dt/2 of the last step, booked if the contact opens
    bool operator==(const State&) const = default;
    // Seen from the partner, n turns over and with it the tangential spring.
    YUXI_HD State mirrored() const {
      State m = *this;
      m.ut = -ut;
      m.n_prev = -n_prev;
      m.owed = -owed;
      return m;
    }
  };

  // The spring constant of (19) for a contact of reduced radius R*: k = (4/3) E* sqrt(R*).
  YUXI_HD static double spring_constant(const Coeffs& c, double r_eff) {
    return 4.0 / 3.0 * c.e_star * std::sqrt(r_eff);
  }
  // The example coefficients of one contact: k = (4/3) E* sqrt(R*), d = a_i + a_j (2 a_i against
  // a flat wall), reference mass 2 m*.
  YUXI_HD static thermo::ExampleCoefficients coefficients(const Coeffs& c, double m_eff,
                                                          double r_eff, double d) {
    return thermo::ExampleCoefficients::of(c.model(), spring_constant(c, r_eff), m_eff, d);
  }

  // Hertz contact time (T1): t_c = 2.9432 (5 m* / (4 k G^{5/2}))^{2/5} v^{-1/5}.
  static double contact_time(const Coeffs& c, double m_eff, double r_eff, double v_impact);
  // A touching contact (overlap > 0); the pair loop calls release() when it opens.
  YUXI_HD static ContactResult evaluate(const ContactGeometry& g, const Coeffs& c, State& s);
  YUXI_HD static double release(const Coeffs&, State& s) {
    const double e = s.stored + s.w_relax + s.owed_energy;
    s = State{};
    return e;
  }
  // u rotated by the rotation that takes the unit vector `from` to the unit vector `to` about
  // their common normal (Rodrigues, with a = from x to, c = from . to):
  // u' = c u + a x u + a (a . u) / (1 + c).
  YUXI_HD static Vec3 rotate_minimal(const Vec3& u, const Vec3& from, const Vec3& to) {
    const double c = dot(from, to);
    if (c <= -1.0 + 1e-12) return -u; // the normal turned over in one step: no unique rotation
    const Vec3 a = cross(from, to);
    return c * u + cross(a, u) + a * (dot(a, u) / (1 + c));
  }
};

// Defined here so that the pair loop, templated on the model, inlines it.
YUXI_ALWAYS_INLINE YUXI_HD ContactResult Thermodynamic::evaluate(const ContactGeometry& g,
                                                                 const Coeffs& c, State& s) {
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
  ut *= portable::exp(-co.relaxation_rate(s.w_relax) * kappa * dt);
  // d. yield (41): back onto the stability boundary (35).
  const double limit = thermo::yield_limit(xi, un);
  const double ut_len = norm(ut);
  if (ut_len > limit) ut *= ut_len > 0 ? limit / ut_len : 0.0;
  const double w_el = thermo::elastic_energy(k, xi, un, norm2(ut));
  double heat = w_before - w_el;
  // e. w_R decays into heat (22).
  double w_relax = s.w_relax * portable::exp(-dt / co.tau);
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

} // namespace yuxi
