// The linear spring-dashpot's scene side (model_scene.hpp): its keys, the LAMMPS preset, its
// example and its state's columns (those of the tangential and rolling sliders).
#pragma once

#include "contact/linear_spring_dashpot.hpp"
#include "contact/model_scene.hpp"
#include "contact/scene_fields.hpp"
#include "contact/state_columns.hpp"

namespace yuxi {

template <> struct ModelScene<LinearSpringDashpot> {
  using Coeffs = LinearSpringDashpot::Coeffs;
  // The scene keys of the coefficients (scene_fields.hpp).
  template <class V> static void fields(V& v, Coeffs& c) {
    v.required("k_n", c.k_n);
    v.optional("k_t", c.k_t);
    v.optional("gamma_n", c.gamma_n);
    v.optional("gamma_t", c.gamma_t);
    friction_fields(v, c.mu_s, c.mu_d);
    slider_fields(v, "k_r", c.k_r, "gamma_r", c.gamma_r, "mu_r", c.mu_r);
    rolling_model_field(v, c.rolling_model);
    v.check(!(c.rolling_model == RollingModel::elastic_plastic && c.mu_r > 0 && c.k_r == 0), "mu_r",
            "mu_r without k_r resists nothing in the elastic-plastic rolling model: give k_r "
            "(2.25 mu_r^2 k_n is usual: docs/models/rolling.md), or rolling_model = "
            "\"constant_torque\"");
    v.choice("friction_cap", c.friction_cap,
             {{"spring", CapOn::spring},
              {"total", CapOn::total},
              {"total_lammps", CapOn::total_lammps}});
    v.choice("tangential_carry", c.carry, {{"rotate", Carry::rotate}, {"project", Carry::project}});
  }
  // The scene's preset = "lammps": LAMMPS gran/hooke/history's conventions as the defaults.
  static void lammps_preset(Coeffs& c) {
    c.friction_cap = CapOn::total_lammps;
    c.carry = Carry::project;
  }
  // In model units (example_units.hpp): k_n = 1, k_t = 2/7, mu = 0.5 and the damping of
  // restitution 0.88.
  static Coeffs example();
};

} // namespace yuxi
