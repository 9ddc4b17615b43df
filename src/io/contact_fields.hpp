// The scene keys of each contact model's pair coefficients, listed once: the same function
// drives the reader (TOML -> Coeffs, with validation) and the writer (Coeffs -> resolved TOML),
// so the two cannot drift apart.
//
// A visitor V provides:
//   required(key, double&)            > 0, must be given
//   optional(key, double&)            >= 0, default: the value already in the field
//   optional_or(key, double&, fallback)  >= 0, default: fallback
//   fraction(key, double&)            in (0, 1], default: the value already in the field
//   choice(key, Enum&, {{"name", value}, ...})
//   check(ok, key, message)           a contradiction between fields (reader only)
#pragma once

#include "contact/contact_model.hpp"

#include <fmt/format.h>
#include <string_view>
#include <utility>

namespace yuxi {

// Static and dynamic friction, mu_d defaulting to mu_s and never above it.
template <class V> void friction_fields(V& v, double& mu_s, double& mu_d) {
  v.optional("mu_s", mu_s);
  v.optional_or("mu_d", mu_d, mu_s);
  v.check(mu_d <= mu_s, "mu_d",
          fmt::format("dynamic friction {} exceeds static friction mu_s = {}", mu_d, mu_s));
}

// A spring-dashpot-slider's stiffness, damping rate and friction coefficient.
template <class V>
void slider_fields(V& v, std::string_view k, double& stiffness, std::string_view gamma,
                   double& rate, std::string_view mu, double& friction) {
  v.optional(k, stiffness);
  v.optional(gamma, rate);
  v.optional(mu, friction);
}

template <class V> void contact_fields(V& v, LinearSpringDashpot::Coeffs& c) {
  v.required("k_n", c.k_n);
  v.optional("k_t", c.k_t);
  v.optional("gamma_n", c.gamma_n);
  v.optional("gamma_t", c.gamma_t);
  friction_fields(v, c.mu_s, c.mu_d);
  slider_fields(v, "k_r", c.k_r, "gamma_r", c.gamma_r, "mu_r", c.mu_r);
  v.choice(
      "friction_cap", c.friction_cap,
      {{"spring", CapOn::spring}, {"total", CapOn::total}, {"total_lammps", CapOn::total_lammps}});
  v.choice("tangential_carry", c.carry, {{"rotate", Carry::rotate}, {"project", Carry::project}});
}

template <class V> void contact_fields(V& v, HertzMindlin::Coeffs& c) {
  v.fraction("restitution", c.restitution);
  v.optional("friction", c.friction);
}

template <class V> void contact_fields(V& v, Luding::Coeffs& c) {
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

// The example model of the thermodynamic law in dimensionless numbers (thermodynamic.hpp);
// E* comes from the materials.
template <class V> void contact_fields(V& v, Thermodynamic::Coeffs& c) {
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

} // namespace yuxi
