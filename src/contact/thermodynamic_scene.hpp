// The thermodynamic law's scene side (model_scene.hpp): its keys, the coefficients completed with
// the materials' elastic constants, its example and its state's columns.
#pragma once

#include "contact/model_scene.hpp"
#include "contact/scene_fields.hpp"
#include "contact/state_columns.hpp"
#include "contact/thermodynamic.hpp"

namespace yuxi {

template <> struct ModelScene<Thermodynamic> {
  using Coeffs = Thermodynamic::Coeffs;
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
};

template <class Field> void columns(const Thermodynamic::State& s, Field&& f) {
  f("un", s.un);
  f("ut", s.ut);
  f("w_relax", s.w_relax);
  f("stored", s.stored);
  f("n_prev", s.n_prev);
  f("delta_prev", s.delta_prev);
  f("owed", s.owed);
  f("owed_energy", s.owed_energy);
}

} // namespace yuxi
