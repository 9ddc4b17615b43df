// A frictionless linear (Hooke) spring with an optional normal dashpot: the normal part of the
// linear spring-dashpot law (linear_spring_dashpot.hpp) on its own, with its conventions.
//
//   F_n = (k_n delta - m_e gamma_n v_n) n      on i (the opposite on j); no tangential force,
//                                              so no torque
//
// delta the overlap [length]; v_n = (v_i - v_j) . n the normal relative velocity, < 0 while
// approaching [length/time] (the spins add nothing along n); m_e = m_i m_j / (m_i + m_j), m_i
// against wall particles and flat walls [mass]; k_n the stiffness [mass/time^2]; gamma_n the
// damping rate [1/time], as in the linear model.
//
// A head-on impact is a damped oscillator, delta'' + gamma_n delta' + (k_n/m_e) delta = 0, of
// damping ratio zeta = gamma_n / (2 sqrt(k_n/m_e)). It lasts t_c = pi / sqrt(k_n/m_e -
// gamma_n^2/4) and rebounds with e = exp(-gamma_n t_c / 2) = exp(-pi zeta / sqrt(1 - zeta^2)) at
// every impact speed: the attractive dashpot force at the end of a contact is not clamped.
//
// Energy: the spring holds k_n delta^2 / 2, reported every step and given back as delta -> 0, so
// an opening contact holds nothing; the dashpot dissipates m_e gamma_n v_n^2 dt a step.
//
// Not LAMMPS's gran/hooke, which adds tangential damping and friction.
#pragma once

#include "contact/contact_geometry.hpp"
#include "core/always_inline.hpp"
#include "core/host_device.hpp"
#include "core/units.hpp"

#include <cmath>
#include <limits>
#include <string_view>

namespace yuxi {

struct Hooke {
  static constexpr std::string_view name = "hooke";

  struct Coeffs {
    double k_n = 0;     // normal stiffness [force/length = mass/time^2]
    double gamma_n = 0; // normal damping rate (force = m_e gamma_n v_n) [1/time]
  };

  // Nothing to remember between steps: the force follows from the overlap and the velocity.
  struct State {
    bool operator==(const State&) const = default;
    YUXI_HD State mirrored() const { return *this; }
  };

  // t_c = pi / sqrt(k_n/m_eff - gamma_n^2/4) [time]; infinite when overdamped.
  static double contact_time(const Coeffs& c, double m_eff, double /*r_eff*/, double /*v_impact*/) {
    const double w2 = c.k_n / m_eff - 0.25 * c.gamma_n * c.gamma_n;
    return w2 > 0 ? pi / std::sqrt(w2) : std::numeric_limits<double>::infinity();
  }

  // A touching contact (overlap > 0); the pair loop calls release() when it opens.
  YUXI_ALWAYS_INLINE YUXI_HD static ContactResult evaluate(const ContactGeometry& g,
                                                           const Coeffs& c, State&) {
    ContactResult r;
    r.touching = true;
    const double vn = dot(g.v_rel, g.n);
    const double fn = c.k_n * g.overlap - g.m_eff * c.gamma_n * vn;
    r.force = fn * g.n;
    r.elastic = 0.5 * c.k_n * g.overlap * g.overlap;
    r.dissipated = g.m_eff * c.gamma_n * vn * vn * g.dt;
    return r;
  }

  // The contact has opened: the state is fresh again and no energy is left in it.
  YUXI_HD static double release(const Coeffs&, State& s) {
    s = State{};
    return 0.0;
  }
};

} // namespace yuxi
