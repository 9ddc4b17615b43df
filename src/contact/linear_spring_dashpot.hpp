// Linear spring-dashpot contact with a tangential spring and separate static and dynamic
// friction: the law of Li & Cai (2008), eq. (5)-(6), after Cundall & Strack (1979) and
// Silbert et al., PRE 64, 051302 (2001). Spec: docs/models/fish-basin.md section 5.
//
//   F_n = k_n delta n - m_e gamma_n v_n                     (normal: spring + dashpot)
//   F_t = -k_t s_t - m_e gamma_t v_t, s_t the tangential spring (frictional_spring.hpp)
//
// Conventions, each selectable (scene keys in brackets), defaults first:
//  - Coulomb limit on the spring force alone, dashpot added after, as in the paper; or on
//    spring + dashpot together, sliding at exactly mu |F_n| (LIGGGHTS); or that with LAMMPS
//    gran/hooke/history's rescaling of the spring [friction_cap = spring|total|total_lammps];
//  - spring carried into the turning tangent plane keeping its length (energy neutral); or
//    projected without rescaling as in LAMMPS [tangential_carry = rotate|project];
//  - static/dynamic friction as a two-state law: a sticking contact slides above mu_s |F_n|,
//    a sliding one sticks again below mu_d |F_n|. Without this hysteresis the spring would
//    reload to mu_s after every step of steady sliding. mu_s = mu_d gives one coefficient.
// Always: m_e = m_i against wall particles and flat walls (LAMMPS: against frozen particles);
// lever arm = radius; no clamp of the attractive dashpot force, so e = exp(-gamma_n t_c / 2)
// exactly (docs/models/validation.md L1).
//
// Optional rolling resistance (rolling_resistance.hpp, docs/models/rolling.md): by default
// (k_r > 0) a spring-dashpot-slider on the rolling displacement, u_r = -a n x (w_i - w_j) with
// a = a_i a_j / (a_i + a_j), torque a n x F_r on i and the opposite on j, Coulomb limit
// mu_r |F_n| (Ai, Chen, Rotter & Ooi, Powder Technol. 206 (2011), model C; Luding 2008); or,
// with rolling_model = "constant_torque", the torque mu_r a |F_n| against the relative rolling
// (their model A).
//
// Energy: springs store k_n delta^2/2 + k_t |s_t|^2/2 (+ k_r |s_r|^2/2); dashpots and sliding
// dissipate as booked by the slider; the spring energy left when a contact opens is lost.
#pragma once

#include "contact/contact_geometry.hpp"
#include "contact/frictional_spring.hpp"
#include "contact/rolling_resistance.hpp"
#include "core/always_inline.hpp"
#include "core/host_device.hpp"

#include <string_view>

namespace yuxi {

struct LinearBatch; // linear_batch.hpp, included at the end of this file

struct LinearSpringDashpot {
  static constexpr std::string_view name = "linear";

  struct Coeffs {
    double k_n = 0;     // normal stiffness [force/length = mass/time^2]
    double k_t = 0;     // tangential stiffness [mass/time^2]
    double gamma_n = 0; // normal damping rate (force = m_e gamma_n v_n) [1/time]
    double gamma_t = 0; // tangential damping rate [1/time]
    double mu_s = 0;    // static friction coefficient [-]
    double mu_d = 0;    // dynamic friction coefficient [-], mu_d <= mu_s
    double k_r = 0;     // rolling stiffness [mass/time^2]; 0 with mu_r = 0: no rolling resistance
    double gamma_r = 0; // rolling damping rate [1/time]
    double mu_r = 0;    // rolling friction coefficient [-]
    CapOn friction_cap = CapOn::spring;
    Carry carry = Carry::rotate;
    RollingModel rolling_model = RollingModel::elastic_plastic;

    YUXI_HD bool rolling() const { return k_r > 0 || mu_r > 0; }
  };

  using State = TangentialRollingState;
  // The pair loop evaluates the law in SIMD batches where every pair of materials allows it.
  using Batch = LinearBatch;

  // Contact time of a normal collision with effective mass m_eff (docs/models/validation.md L1):
  // t_c = pi / sqrt(k_n/m_eff - gamma_n^2/4). Infinite when overdamped.
  static double contact_time(const Coeffs& c, double m_eff, double r_eff, double v_impact);

  // A touching contact (overlap > 0); the pair loop calls release() when it opens.
  YUXI_HD static ContactResult evaluate(const ContactGeometry& g, const Coeffs& c, State& s);
  // The contact has opened: resets the state and returns the elastic energy it still held.
  YUXI_HD static double release(const Coeffs&, State& s) { return yuxi::release(s); }
};

// Defined here so that the pair loop, templated on the model, inlines it.
YUXI_ALWAYS_INLINE YUXI_HD ContactResult LinearSpringDashpot::evaluate(const ContactGeometry& g,
                                                                       const Coeffs& c, State& s) {
  ContactResult r;
  r.touching = true;
  const auto [vn, vt] = split_contact_velocity(g);

  const double fn = c.k_n * g.overlap - g.m_eff * c.gamma_n * vn;
  const Vec3 carried = c.carry == Carry::rotate
                           ? carry_in_plane(s.tangential.spring, g.n)
                           : s.tangential.spring - dot(s.tangential.spring, g.n) * g.n;
  const SliderLaw tangential{c.k_t, g.m_eff * c.gamma_t, c.mu_s, c.mu_d, c.friction_cap};
  const SliderResult t = slide(s.tangential, carried, vt, fn, tangential, g.dt);

  r.add_contact_force(g, fn, t.force);
  r.elastic = 0.5 * c.k_n * g.overlap * g.overlap + s.tangential.stored();
  r.dissipated = g.m_eff * c.gamma_n * vn * vn * g.dt + t.dissipated;

  if (c.rolling())
    add_rolling_resistance(r, g, c.rolling_model, c.mu_r, fn,
                           SliderLaw{c.k_r, g.m_eff * c.gamma_r, c.mu_r, c.mu_r, CapOn::total}, fn,
                           s.rolling);
  return r;
}

} // namespace yuxi
