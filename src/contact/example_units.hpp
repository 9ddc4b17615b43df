// The model units in which every contact model gives example coefficients (ModelScene<Model>::
// example()), the parameter sets of `yuxi collide` (docs/models/thermodynamic-contact.md section
// 8): two grains of mass m = 1 and radius a = 0.5, so d = 2a = 1 and m* = 1/2; every model's normal
// stiffness is 1 there (Hertz: (4/3) E* sqrt(R*) = 1 at R* = 1/4, i.e. E* = 1.5), friction 0.5,
// tangential stiffness 2/7 of the normal one where it is free.
#pragma once

#include "core/units.hpp"

#include <cmath>

namespace yuxi::example_units {

inline constexpr double reduced_mass = 0.5;     // m* of two grains of mass 1 [mass]
inline constexpr double normal_stiffness = 1.0; // k_n of a linear spring [mass/time^2]
inline constexpr double e_star = 1.5;           // E* of two equal grains [force/length^2]
inline constexpr double poisson = 0.3;          // their Poisson ratio [-]
inline constexpr double friction = 0.5;         // mu [-]
// The restitution of the speed-independent models: REF's e near v0 = 1e-3 [-].
inline constexpr double restitution = 0.88;

// The damping rate gamma of a linear spring k with dashpot force m* gamma v_n that gives the
// normal restitution e: e = exp(-gamma t_c / 2), t_c = pi / sqrt(k/m* - gamma^2/4), so
// gamma = 2 b omega with b = -ln(e) / pi, omega = sqrt(k / (m* (1 + b^2))) [1/time].
inline double linear_damping_rate(double e, double k, double m_eff) {
  const double b = -std::log(e) / pi;
  const double omega = std::sqrt(k / m_eff / (1 + b * b));
  return 2 * b * omega;
}

} // namespace yuxi::example_units
