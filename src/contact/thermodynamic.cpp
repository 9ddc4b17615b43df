#include "contact/thermodynamic.hpp"

#include "contact/example_units.hpp"
#include "contact/frictional_spring.hpp"
#include "contact/hertz_mindlin.hpp"
#include "contact/thermodynamic_scene.hpp"

#include <algorithm>
#include <cmath>

namespace yuxi {

Thermodynamic::Coeffs ModelScene<Thermodynamic>::with_materials(const Coeffs& c, double youngs_1,
                                                                double poisson_1, double youngs_2,
                                                                double poisson_2) {
  Coeffs out = c;
  out.e_star = HertzMindlin::mix(youngs_1, poisson_1, youngs_2, poisson_2, 1.0, 0.0).e_star;
  return out;
}

Thermodynamic::Coeffs ModelScene<Thermodynamic>::example() {
  Coeffs c;
  c.e_star = example_units::e_star;
  return c;
}

double Thermodynamic::contact_time(const Coeffs& c, double m_eff, double r_eff, double v) {
  const double k = spring_constant(c, r_eff) * std::pow(c.gear, 2.5);
  const double t_normal = 2.9432 * std::pow(5 * m_eff / (4 * k), 0.4) * std::pow(v, -0.2);
  // The tangential spring is k_t/k_n = 4/(3 xi) times stiffer than the normal one (spec 4) and
  // acts on 2/7 of the mass for rolling spheres: its half period is shorter when that exceeds 1.
  const double ratio = 4.0 / (3.0 * thermo::xi_of_friction(c.friction)) * 3.5;
  return t_normal / std::sqrt(std::max(1.0, ratio));
}

} // namespace yuxi
