#include "contact/linear_spring_dashpot.hpp"

#include "contact/example_units.hpp"
#include "contact/linear_spring_dashpot_scene.hpp"
#include "core/units.hpp"

#include <limits>

namespace yuxi {

double LinearSpringDashpot::contact_time(const Coeffs& c, double m_eff, double, double) {
  const double w2 = c.k_n / m_eff - 0.25 * c.gamma_n * c.gamma_n;
  return w2 > 0 ? pi / std::sqrt(w2) : std::numeric_limits<double>::infinity();
}

LinearSpringDashpot::Coeffs ModelScene<LinearSpringDashpot>::example() {
  using namespace example_units;
  Coeffs c;
  c.k_n = normal_stiffness;
  c.k_t = 2.0 / 7.0 * normal_stiffness;
  c.gamma_n = linear_damping_rate(restitution, normal_stiffness, reduced_mass);
  c.mu_s = c.mu_d = friction;
  return c;
}

} // namespace yuxi
