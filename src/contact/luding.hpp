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
#include "contact/scene_fields.hpp"

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

  // The scene keys of the coefficients (scene_fields.hpp).
  template <class V> static void fields(V& v, Coeffs& c) {
    v.required("k1", c.k1);
    v.optional_or("kp", c.kp, c.k1);
    v.check(c.kp >= c.k1, "kp", fmt::format("kp = {} must be at least k1 = {}", c.kp, c.k1));
    v.optional("kc", c.kc);
    v.fraction("phi_f", c.phi_f);
    v.optional("gamma_n", c.gamma_n);
    v.optional("k_t", c.k_t);
    v.optional("gamma_t", c.gamma_t);
    friction_fields(v, c.mu_s, c.mu_d);
    slider_fields(v, "k_r", c.k_r, "gamma_r", c.gamma_r, "mu_r", c.mu_r);
    slider_fields(v, "k_o", c.k_o, "gamma_o", c.gamma_o, "mu_o", c.mu_o);
  }
  // Example coefficients in model units (example_units.hpp): k1 = 1 and plastic hysteresis up
  // to kp = 5, so e = sqrt(k1/k2(delta_max)) falls from 1 to sqrt(1/5); k_t = 2/7, mu = 0.5.
  static Coeffs example();

  struct State {
    double delta_max = 0; // largest overlap reached (lowered on the adhesive branch)
    double delta = 0;     // overlap at the last step
    double f_hys = 0;     // hysteretic normal force at the last step
    double stored_n = 0;  // recoverable normal energy at the last step
    SliderState tangential, rolling, torsion;
    bool operator==(const State&) const = default;
    // Seen from the partner, n turns over: the tangential and torsion springs change sign,
    // the rolling spring does not.
    State mirrored() const {
      State m = *this;
      m.tangential.spring = -tangential.spring;
      m.torsion.spring = -torsion.spring;
      return m;
    }
    template <class Field> void fields(Field&& f) const {
      f("delta_max", delta_max);
      f("delta", delta);
      f("f_hys", f_hys);
      f("stored_n", stored_n);
      tangential.fields("tangential", f);
      rolling.fields("rolling", f);
      torsion.fields("torsion", f);
    }
  };

  // Half period of the stiffest (unloading) spring with damping: pi / sqrt(kp/m - gamma^2/4).
  static double contact_time(const Coeffs& c, double m_eff, double r_eff, double v_impact);
  // A touching contact (overlap > 0); the pair loop calls release() when it opens.
  static ContactResult evaluate(const ContactGeometry& g, const Coeffs& c, State& s);
  static double release(const Coeffs& c, State& s);
};

} // namespace yuxi
