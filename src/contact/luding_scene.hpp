// Luding's scene side (model_scene.hpp): its keys, its example and its state's columns.
#pragma once

#include "contact/luding.hpp"
#include "contact/model_scene.hpp"
#include "contact/scene_fields.hpp"
#include "contact/state_columns.hpp"

namespace yuxi {

template <> struct ModelScene<Luding> {
  using Coeffs = Luding::Coeffs;
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
};

template <class Field> void columns(const Luding::State& s, Field&& f) {
  f("delta_max", s.delta_max);
  f("delta", s.delta);
  f("f_hys", s.f_hys);
  f("stored_n", s.stored_n);
  columns(s.tangential, "tangential", f);
  columns(s.rolling, "rolling", f);
  columns(s.torsion, "torsion", f);
}

} // namespace yuxi
