// Luding's linear elasto-plastic adhesive contact with tangential, rolling and torsion springs:
// S. Luding, "Cohesive, frictional powders: contact models for tension", Granular Matter 10,
// 235-246 (2008), sections 2.2-2.5.
//
// Normal (hysteretic spring plus dashpot), delta_max the largest overlap so far:
//   k2(delta_max) = k1 + (kp - k1) delta_max / delta_p   (kp once delta_max >= delta_p),
//   delta_p = kp / (kp - k1) phi_f 2 a12,  a12 = a_i a_j / (a_i + a_j)
//   delta_0 = (1 - k1/k2) delta_max                       (the plastic overlap)
//   f_hys = k1 delta               if k2 (delta - delta_0) >= k1 delta   (virgin loading)
//         = k2 (delta - delta_0)   if k1 delta > k2 (delta - delta_0) > -kc delta
//         = -kc delta              otherwise (adhesive limit; delta_max is lowered so that
//                                  reloading starts from here)
//   f_n = f_hys - m_e gamma_n v_n
// Without damping and adhesion an impact that reaches delta_p rebounds with e = sqrt(k1/kp).
//
// Tangential, rolling and torsion: spring-dashpot-sliders (frictional_spring.hpp) with limits
// mu |f_n + kc delta| (adhesion presses the contact), Coulomb limit on spring + dashpot:
//   tangential  u_t = v_c - (v_c . n) n,          torque -a_i n x F_t on i, -a_j n x F_t on j
//   rolling     u_r = -a12 n x (w_i - w_j),       torque  a12 n x F_r on i, the opposite on j
//   torsion     u_o =  a12 ((w_i - w_j) . n) n,   torque  a12 F_o on i, the opposite on j
// Lever arms are the radii, as for the other models (Luding uses a - delta/2; the difference is
// of order delta/a, and velocity and torque use the same arm, so energy is consistent).
//
// Energy: the normal spring holds k2 (delta - delta_0)^2 / 2 that unloading gives back; each
// step books the work done into it, (f_old + f_new)/2 (delta_new - delta_old), less the change
// of that energy, as dissipated (plastic work and adhesive rupture).
#pragma once

#include "contact/contact_geometry.hpp"
#include "contact/frictional_spring.hpp"
#include "core/always_inline.hpp"
#include "core/host_device.hpp"

#include <algorithm>
#include <string_view>

namespace yuxi {

struct Luding {
  static constexpr std::string_view name = "luding";

  struct Coeffs {
    double k1 = 0;       // loading stiffness [mass/time^2]
    double kp = 0;       // largest unloading stiffness, kp >= k1 [mass/time^2]
    double kc = 0;       // adhesive stiffness [mass/time^2]
    double phi_f = 0.05; // plastic-flow overlap, as a fraction of 2 a12 [-]
    double gamma_n = 0;  // normal damping rate [1/time]
    double k_t = 0, gamma_t = 0, mu_s = 0, mu_d = 0; // tangential
    double k_r = 0, gamma_r = 0, mu_r = 0;           // rolling
    double k_o = 0, gamma_o = 0, mu_o = 0;           // torsion
  };

  struct State {
    double delta_max = 0; // largest overlap reached (lowered on the adhesive branch)
    double delta = 0;     // overlap at the last step
    double f_hys = 0;     // hysteretic normal force at the last step
    double stored_n = 0;  // recoverable normal energy at the last step
    SliderState tangential, rolling, torsion;
    bool operator==(const State&) const = default;
    // Seen from the partner, n turns over: the tangential and torsion springs change sign,
    // the rolling spring does not.
    YUXI_HD State mirrored() const {
      State m = *this;
      m.tangential.spring = -tangential.spring;
      m.torsion.spring = -torsion.spring;
      return m;
    }
  };

  // Half period of the stiffest (unloading) spring with damping: pi / sqrt(kp/m - gamma^2/4).
  static double contact_time(const Coeffs& c, double m_eff, double r_eff, double v_impact);
  // A touching contact (overlap > 0); the pair loop calls release() when it opens.
  YUXI_HD static ContactResult evaluate(const ContactGeometry& g, const Coeffs& c, State& s);
  YUXI_HD static double release(const Coeffs&, State& s) {
    const double e = s.stored_n + yuxi::release(s.tangential) + yuxi::release(s.rolling) +
                     yuxi::release(s.torsion);
    s = State{};
    return e;
  }
  // k2(delta_max) (above): kp once delta_max >= delta_p.
  YUXI_HD static double unloading_stiffness(const Coeffs& c, double delta_max, double a12) {
    if (c.kp <= c.k1) return c.k1;
    const double delta_p = c.kp / (c.kp - c.k1) * c.phi_f * 2 * a12;
    return delta_max >= delta_p ? c.kp : c.k1 + (c.kp - c.k1) * delta_max / delta_p;
  }
};

// Defined here so that the pair loop, templated on the model, inlines it.
YUXI_ALWAYS_INLINE YUXI_HD ContactResult Luding::evaluate(const ContactGeometry& g, const Coeffs& c,
                                                          State& s) {
  ContactResult r;
  r.touching = true;
  const double delta = g.overlap;
  const double a12 = g.r_eff;

  // Hysteretic normal spring.
  double k2 = unloading_stiffness(c, s.delta_max, a12);
  double delta0 = (1 - c.k1 / k2) * s.delta_max;
  double f_hys = k2 * (delta - delta0);
  if (f_hys >= c.k1 * delta) { // virgin loading
    f_hys = c.k1 * delta;
    s.delta_max = delta;
    k2 = unloading_stiffness(c, delta, a12);
    delta0 = (1 - c.k1 / k2) * delta;
  } else if (f_hys <= -c.kc * delta) { // adhesive limit: move the unloading branch here
    f_hys = -c.kc * delta;
    s.delta_max = (k2 + c.kc) / (k2 - c.k1) * delta;
    delta0 = (1 - c.k1 / k2) * s.delta_max;
  }
  const double stored_n = 0.5 * k2 * (delta - delta0) * (delta - delta0);
  const double work_in = 0.5 * (s.f_hys + f_hys) * (delta - s.delta);
  const double normal_loss = work_in - (stored_n - s.stored_n);
  s.delta = delta;
  s.f_hys = f_hys;
  s.stored_n = stored_n;

  const auto [vn, vt] = split_contact_velocity(g);
  const double fn = f_hys - g.m_eff * c.gamma_n * vn;
  const double pressing = std::max(fn + c.kc * delta, 0.0); // no friction without compression

  const SliderLaw tangential{c.k_t, g.m_eff * c.gamma_t, c.mu_s, c.mu_d, CapOn::total};
  const SliderResult t =
      slide(s.tangential, carry_in_plane(s.tangential.spring, g.n), vt, pressing, tangential, g.dt);
  const Vec3 w_rel = g.w_i - g.w_j;
  const Vec3 u_r = -a12 * cross(g.n, w_rel);
  const SliderLaw rolling{c.k_r, g.m_eff * c.gamma_r, c.mu_r, c.mu_r, CapOn::total};
  const SliderResult rr =
      slide(s.rolling, carry_in_plane(s.rolling.spring, g.n), u_r, pressing, rolling, g.dt);
  const Vec3 u_o = (a12 * dot(w_rel, g.n)) * g.n;
  const SliderLaw torsion{c.k_o, g.m_eff * c.gamma_o, c.mu_o, c.mu_o, CapOn::total};
  const SliderResult tor =
      slide(s.torsion, carry_along(s.torsion.spring, g.n), u_o, pressing, torsion, g.dt);

  r.add_contact_force(g, fn, t.force);
  const Vec3 roll = a12 * cross(g.n, rr.force);
  const Vec3 twist = a12 * tor.force;
  r.torque_i += roll + twist;
  r.torque_j -= roll + twist;
  r.elastic = stored_n + s.tangential.stored() + s.rolling.stored() + s.torsion.stored();
  r.dissipated = g.m_eff * c.gamma_n * vn * vn * g.dt + normal_loss + t.dissipated + rr.dissipated +
                 tor.dissipated;
  return r;
}

} // namespace yuxi
