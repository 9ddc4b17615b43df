// How a contact model names its pair coefficients in a scene file. Each model lists its keys
// once, in `template <class V> static void fields(V& v, Coeffs& c)`; the same function drives
// the scene reader (TOML -> Coeffs, with validation) and the scene writer (Coeffs -> resolved
// TOML), so the two cannot drift apart.
//
// A visitor V provides:
//   required(key, double&)               > 0, must be given
//   optional(key, double&)               >= 0, default: the value already in the field
//   optional_or(key, double&, fallback)  >= 0, default: fallback
//   fraction(key, double&)               in (0, 1], default: the value already in the field
//   choice(key, Enum&, {{"name", value}, ...})
//   check(ok, key, message)              a contradiction between fields (reader only)
#pragma once

#include <fmt/format.h>
#include <initializer_list>
#include <string>
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

// Which rolling-resistance model (rolling_resistance.hpp).
template <class V, class E> void rolling_model_field(V& v, E& model) {
  v.choice("rolling_model", model,
           {{"elastic_plastic", E::elastic_plastic}, {"constant_torque", E::constant_torque}});
}

// A visitor that accepts every field and does nothing: the registry (contact_model.hpp) checks
// with it that each model's fields() is written against the interface above.
struct IgnoreFields {
  void required(std::string_view, double&) {}
  void optional(std::string_view, double&) {}
  void optional_or(std::string_view, double&, double) {}
  void fraction(std::string_view, double&) {}
  template <class E>
  void choice(std::string_view, E&, std::initializer_list<std::pair<std::string_view, E>>) {}
  void check(bool, std::string_view, const std::string&) {}
};

} // namespace yuxi
