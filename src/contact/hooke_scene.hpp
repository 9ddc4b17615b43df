// The Hooke spring's scene side (model_scene.hpp): its keys, example and state columns.
#pragma once

#include "contact/example_units.hpp"
#include "contact/hooke.hpp"
#include "contact/model_scene.hpp"
#include "contact/scene_fields.hpp"

namespace yuxi {

template <> struct ModelScene<Hooke> {
  using Coeffs = Hooke::Coeffs;
  template <class V> static void fields(V& v, Coeffs& c) {
    v.required("k_n", c.k_n);
    v.optional("gamma_n", c.gamma_n);
  }
  // In model units (example_units.hpp): k_n = 1 and the damping of restitution 0.88.
  static Coeffs example() {
    using namespace example_units;
    return {normal_stiffness, linear_damping_rate(restitution, normal_stiffness, reduced_mass)};
  }
};

// Nothing to remember, no columns.
template <class Field> void columns(const Hooke::State&, Field&&) {}

} // namespace yuxi
