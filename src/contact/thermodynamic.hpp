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
#include "contact/scene_fields.hpp"
#include "contact/thermodynamic_law.hpp"

#include <cstdint>
#include <string_view>

namespace yuxi {

enum class ViscosityChannel : std::uint8_t { relaxation, heat };

struct Thermodynamic {
  static constexpr std::string_view name = "thermodynamic";

  struct Coeffs {
    double e_star = 0;      // E* of the pair (as for Hertz-Mindlin) [force/length^2]
    double friction = 0.5;  // mu = sqrt(2/xi) (36) [-]
    double gear = 1;        // G inside the contact (38) [-]
    double eta_hat = 0.3;   // viscosity (39), in units of sqrt(m k d^{1/2}) [-]
    double eta_power = 0.5; // overlap exponent of the viscosity (39) [-]
    double lambda_hat = 10; // tangential relaxation by w_R (40) [-]
    double tau_hat = 5;     // decay time of w_R in units of t0 (22) [-]
    ViscosityChannel viscosity_to = ViscosityChannel::relaxation;

    thermo::ExampleModel model() const;
  };

  // The scene keys: the example model of the law in dimensionless numbers (scene_fields.hpp);
  // E* comes from the materials.
  template <class V> static void fields(V& v, Coeffs& c) {
    v.optional("friction", c.friction);
    v.check(c.friction > 0, "friction",
            "must be positive: it fixes xi = 2 / friction^2 of the elastic energy");
    v.fraction("gear", c.gear);
    v.optional("eta_hat", c.eta_hat);
    v.optional("eta_power", c.eta_power);
    v.optional("lambda_hat", c.lambda_hat);
    v.optional("tau_hat", c.tau_hat);
    v.check(c.tau_hat > 0, "tau_hat", "the decay time of the relaxation energy must be positive");
    v.choice("viscosity_to", c.viscosity_to,
             {{"relaxation", ViscosityChannel::relaxation}, {"heat", ViscosityChannel::heat}});
  }
  // The coefficients read from a scene completed with the two materials' elastic constants:
  // E* mixed as for Hertz-Mindlin, so that k = (4/3) E* sqrt(R*).
  static Coeffs with_materials(const Coeffs& c, double youngs_1, double poisson_1, double youngs_2,
                               double poisson_2);
  // Example coefficients in model units (example_units.hpp): k = (4/3) E* sqrt(R*) = 1 and the
  // spec's parameter set REF (section 6.3).
  static Coeffs example();

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
    State mirrored() const {
      State m = *this;
      m.ut = -ut;
      m.n_prev = -n_prev;
      m.owed = -owed;
      return m;
    }
    template <class Field> void fields(Field&& f) const {
      f("un", un);
      f("ut", ut);
      f("w_relax", w_relax);
      f("stored", stored);
      f("n_prev", n_prev);
      f("delta_prev", delta_prev);
      f("owed", owed);
      f("owed_energy", owed_energy);
    }
  };

  // The spring constant of (19) for a contact of reduced radius R*: k = (4/3) E* sqrt(R*).
  static double spring_constant(const Coeffs& c, double r_eff) {
    return 4.0 / 3.0 * c.e_star * std::sqrt(r_eff);
  }
  // The example coefficients of one contact: k = (4/3) E* sqrt(R*), d = a_i + a_j (2 a_i against
  // a flat wall), reference mass 2 m*.
  static thermo::ExampleCoefficients coefficients(const Coeffs& c, double m_eff, double r_eff,
                                                  double d);

  // Hertz contact time (T1): t_c = 2.9432 (5 m* / (4 k G^{5/2}))^{2/5} v^{-1/5}.
  static double contact_time(const Coeffs& c, double m_eff, double r_eff, double v_impact);
  // A touching contact (overlap > 0); the pair loop calls release() when it opens.
  static ContactResult evaluate(const ContactGeometry& g, const Coeffs& c, State& s);
  static double release(const Coeffs& c, State& s);
};

} // namespace yuxi
