// Hertz-Mindlin's scene side (model_scene.hpp): its keys, the coefficients completed with the
// materials' elastic constants, its example, and its state's columns (the tangential and
// rolling sliders').
#pragma once

#include "contact/hertz_mindlin.hpp"
#include "contact/model_scene.hpp"
#include "contact/scene_fields.hpp"
#include "contact/state_columns.hpp"

namespace yuxi {

template <> struct ModelScene<HertzMindlin> {
  using Coeffs = HertzMindlin::Coeffs;
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
    Coeffs mixed =
        HertzMindlin::mix(youngs_1, poisson_1, youngs_2, poisson_2, c.restitution, c.friction);
    mixed.mu_r = c.mu_r;
    mixed.rolling_model = c.rolling_model;
    return mixed;
  }
  // Example coefficients in model units (example_units.hpp): (4/3) E* sqrt(R*) = 1, restitution
  // 0.88, friction 0.5.
  static Coeffs example();
};

} // namespace yuxi
