#include "contact/luding.hpp"

#include "contact/example_units.hpp"
#include "contact/luding_scene.hpp"
#include "core/units.hpp"

#include <algorithm>
#include <limits>

namespace yuxi {

Luding::Coeffs ModelScene<Luding>::example() {
  using namespace example_units;
  Coeffs c;
  c.k1 = normal_stiffness;
  c.kp = 5 * normal_stiffness;
  c.phi_f = 0.05;
  c.k_t = 2.0 / 7.0 * normal_stiffness;
  c.mu_s = c.mu_d = friction;
  return c;
}

double Luding::contact_time(const Coeffs& c, double m_eff, double, double) {
  const double w2 = std::max(c.kp, c.k1) / m_eff - 0.25 * c.gamma_n * c.gamma_n;
  return w2 > 0 ? pi / std::sqrt(w2) : std::numeric_limits<double>::infinity();
}

} // namespace yuxi
