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
#include "contact/scene_fields.hpp"

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
  };

  // Derived coefficients from the two materials (a rigid material has E = infinity).
  static Coeffs mix(double youngs_1, double poisson_1, double youngs_2, double poisson_2,
                    double restitution, double friction);

  // The scene keys of the coefficients (scene_fields.hpp); E* and G* come from the materials.
  template <class V> static void fields(V& v, Coeffs& c) {
    v.fraction("restitution", c.restitution);
    v.optional("friction", c.friction);
    v.optional("mu_r", c.mu_r);
    rolling_model_field(v, c.rolling_model);
  }
  // The coefficients read from a scene completed with the two materials' elastic constants.
  static Coeffs with_materials(const Coeffs& c, double youngs_1, double poisson_1, double youngs_2,
                               double poisson_2) {
    Coeffs mixed = mix(youngs_1, poisson_1, youngs_2, poisson_2, c.restitution, c.friction);
    mixed.mu_r = c.mu_r;
    mixed.rolling_model = c.rolling_model;
    return mixed;
  }
  // Example coefficients in model units (example_units.hpp): (4/3) E* sqrt(R*) = 1, restitution
  // 0.88, friction 0.5.
  static Coeffs example();

  using State = TangentialRollingState;

  // Hertz contact time at impact speed v (docs/models/validation.md section 2):
  // t_c = 2.94328 delta_max / v, delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^{2/5}.
  static double contact_time(const Coeffs& c, double m_eff, double r_eff, double v_impact);

  // A touching contact (overlap > 0); the pair loop calls release() when it opens.
  static ContactResult evaluate(const ContactGeometry& g, const Coeffs& c, State& s);
  static double release(const Coeffs&, State& s);
};

} // namespace yuxi
