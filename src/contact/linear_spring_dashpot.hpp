// Linear spring-dashpot contact with a tangential spring and separate static and dynamic
// friction: the law of Li & Cai (2008), eq. (5)-(6), after Cundall & Strack (1979) and
// Silbert et al., PRE 64, 051302 (2001). Spec: fish_basin.md section 5.
//
//   F_n = k_n delta n - m_e gamma_n v_n                     (normal: spring + dashpot)
//   s_t += v_t dt   (tangential spring, kept in the tangent plane as n turns, norm preserved)
//   F_t = -k_t s_t - m_e gamma_t v_t   while sticking
//   F_t = -mu_d |F_n| s_t/|s_t| - m_e gamma_t v_t, with k_t |s_t| = mu_d |F_n|, while sliding
//
// Static/dynamic friction as a two-state law: a sticking contact starts to slide when the
// spring force would exceed mu_s |F_n|; a sliding contact keeps sliding while the spring would
// exceed mu_d |F_n| and sticks again only below it. Without this hysteresis the spring would
// reload to mu_s after every step of steady sliding and the mean friction would exceed mu_d.
//
// Energy: the springs store k_n delta^2/2 + k_t |s_t|^2/2; the dashpots dissipate
// (m_e gamma_n v_n^2 + m_e gamma_t v_t^2) dt per step; sliding dissipates the work done into the
// tangential spring less the rise of its energy; what the spring holds when the contact opens
// is lost. No clamp of the attractive dashpot force: with it the restitution is
// exactly e = exp(-gamma_n t_c / 2) (validation.md L1).
#pragma once

#include "contact/contact_geometry.hpp"

#include <cmath>
#include <cstdint>
#include <string_view>

namespace yuxi {

struct LinearSpringDashpot {
  static constexpr std::string_view name = "linear";

  struct Coeffs {
    double k_n = 0;     // normal stiffness [force/length = mass/time^2]
    double k_t = 0;     // tangential stiffness [mass/time^2]
    double gamma_n = 0; // normal damping rate (force = m_e gamma_n v_n) [1/time]
    double gamma_t = 0; // tangential damping rate [1/time]
    double mu_s = 0;    // static friction coefficient [-]
    double mu_d = 0;    // dynamic friction coefficient [-], mu_d <= mu_s
  };

  struct State {
    Vec3 spring;               // tangential spring s_t, in the tangent plane [length]
    std::uint32_t sliding = 0; // 1 while the contact slides
    bool operator==(const State&) const = default;
    // The same contact seen from the partner: n and s_t change sign.
    State mirrored() const { return {-spring, sliding}; }
  };

  // Contact time of a normal collision with effective mass m_eff (validation.md L1):
  // t_c = pi / sqrt(k_n/m_eff - gamma_n^2/4). Infinite when overdamped.
  static double contact_time(const Coeffs& c, double m_eff, double r_eff, double v_impact);

  static ContactResult evaluate(const ContactGeometry& g, const Coeffs& c, State& s);

  // The contact has opened: resets the state and returns the elastic energy it still held,
  // which is lost to the grains (booked as dissipated).
  static double release(const Coeffs& c, State& s);
};

} // namespace yuxi
