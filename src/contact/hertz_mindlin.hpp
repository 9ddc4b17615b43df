// Hertz-Mindlin contact with Tsuji-type damping, the model of Chung & Ooi (2011) and of most
// DEM codes (EDEM, LIGGGHTS "hertz/tangential_history").
// Spec: docs/models/validation.md section 0.2 and 2.
//
//   normal:     F_n = (4/3) E* sqrt(R*) delta^{3/2} - eta_n v_n,
//               eta_n = -2 sqrt(5/6) beta sqrt(S_n m*),  S_n = 2 E* sqrt(R* delta)
//   tangential: s_t += v_t dt (kept in the tangent plane),  S_t = 8 G* sqrt(R* delta)
//               F_t = -S_t s_t - eta_t v_t,  eta_t = -2 sqrt(5/6) beta sqrt(S_t m*)
//               capped at mu max(F_n, 0): a sliding contact exerts mu F_n, carried by the
//               spring; no friction while the dashpot pulls the surfaces together
//   beta = ln(e) / sqrt(ln^2(e) + pi^2)
// With this damping the normal restitution coefficient equals e at every impact speed
// (Tsuji, Tanaka & Ishida 1992; docs/models/validation.md Test 3, "attractive force allowed").
//
// Optional rolling resistance, mu_r > 0 (rolling_resistance.hpp, docs/models/rolling.md): the
// elastic-plastic model with the stiffness of LIGGGHTS' "epsd2", k_r = 2.25 mu_r^2 S_n on the
// rolling displacement (a torque stiffness 2.25 mu_r^2 S_n R*^2), no damping, capped at
// mu_r |F_n|; or, with rolling_model = "constant_torque", the torque mu_r R* |F_n| against the
// relative rolling.
//
// Energy: stored (8/15) E* sqrt(R*) delta^{5/2} + S_t |s_t|^2 / 2 (+ the rolling spring's). The
// tangential spring's stiffness follows the overlap (Mindlin's no-slip law), which is not
// conservative by itself: each step books as dissipated the work done into the spring, S_t (s_old +
// s_new)/2 . ds, less the change of its stored energy, so the energy books close whatever the path.
#pragma once

#include "contact/contact_geometry.hpp"
#include "contact/frictional_spring.hpp"
#include "contact/rolling_resistance.hpp"
#include "core/always_inline.hpp"
#include "core/host_device.hpp"

#include <cstdint>
#include <string_view>

namespace yuxi {

struct HertzMindlin {
  static constexpr std::string_view name = "hertz_mindlin";

  struct Coeffs {
    double e_star = 0;      // E*, 1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2 [force/length^2]
    double g_star = 0;      // G*, 1/G* = (2-nu1)/G1 + (2-nu2)/G2 [force/length^2]
    double restitution = 1; // e, speed-independent normal restitution [-]
    double friction = 0;    // mu [-]
    double beta = 0;        // ln e / sqrt(ln^2 e + pi^2), derived from e [-]
    double mu_r = 0;        // rolling friction coefficient [-]; 0: no rolling resistance
    RollingModel rolling_model = RollingModel::elastic_plastic;

    YUXI_HD bool rolling() const { return mu_r > 0; }
  };

  // Derived coefficients from the two materials (a rigid material has E = infinity).
  static Coeffs mix(double youngs_1, double poisson_1, double youngs_2, double poisson_2,
                    double restitution, double friction);

  using State = TangentialRollingState;

  // Hertz contact time at impact speed v (docs/models/validation.md section 2):
  // t_c = 2.94328 delta_max / v, delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^{2/5}.
  static double contact_time(const Coeffs& c, double m_eff, double r_eff, double v_impact);

  // A touching contact (overlap > 0); the pair loop calls release() when it opens.
  YUXI_HD static ContactResult evaluate(const ContactGeometry& g, const Coeffs& c, State& s);
  YUXI_HD static double release(const Coeffs&, State& s) { return yuxi::release(s); }
};

// Defined here so that the pair loop, templated on the model, inlines it.
YUXI_ALWAYS_INLINE YUXI_HD ContactResult HertzMindlin::evaluate(const ContactGeometry& g,
                                                                const Coeffs& c, State& s) {
  const double sqrt_5_6 = std::sqrt(5.0 / 6.0);
  ContactResult r;
  r.touching = true;
  const auto [vn, vt] = split_contact_velocity(g);

  const double root = std::sqrt(g.r_eff * g.overlap); // sqrt(R* delta)
  const double s_n = 2 * c.e_star * root;             // normal tangent stiffness dF/d(delta)
  const double s_t = 8 * c.g_star * root;             // Mindlin tangential stiffness
  const double eta_n = -2 * sqrt_5_6 * c.beta * std::sqrt(s_n * g.m_eff);
  const double eta_t = -2 * sqrt_5_6 * c.beta * std::sqrt(s_t * g.m_eff);

  const double fn = (4.0 / 3.0) * c.e_star * root * g.overlap - eta_n * vn;
  const SliderLaw tangential{s_t, eta_t, c.friction, c.friction, CapOn::total};
  // No friction while the dashpot pulls the surfaces together (F_n < 0 at the end of an
  // impact): there is no compression to resist sliding.
  const SliderResult t = slide(s.tangential, carry_in_plane(s.tangential.spring, g.n), vt,
                               std::max(fn, 0.0), tangential, g.dt);

  r.add_contact_force(g, fn, t.force);
  r.elastic = 0.4 * (4.0 / 3.0) * c.e_star * root * g.overlap * g.overlap + s.tangential.stored();
  r.dissipated = eta_n * vn * vn * g.dt + t.dissipated;
  // (epsd: LIGGGHTS epsd2's torque stiffness 2.25 mu_r^2 S_n R*^2, as a force on u_r)
  if (c.rolling())
    add_rolling_resistance(
        r, g, c.rolling_model, c.mu_r, fn,
        SliderLaw{2.25 * c.mu_r * c.mu_r * s_n, 0.0, c.mu_r, c.mu_r, CapOn::total},
        std::max(fn, 0.0), s.rolling);
  return r;
}

} // namespace yuxi
