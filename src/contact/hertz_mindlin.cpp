#include "contact/hertz_mindlin.hpp"

#include "contact/example_units.hpp"
#include "contact/hertz_mindlin_scene.hpp"
#include "core/units.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace yuxi {
namespace {

// 1/E* contribution of one body; zero for a rigid one.
double compliance(double youngs, double poisson) {
  return std::isinf(youngs) ? 0.0 : (1 - poisson * poisson) / youngs;
}

// 1/G* contribution of one body, G = E / (2 (1 + nu)).
double shear_compliance(double youngs, double poisson) {
  return std::isinf(youngs) ? 0.0 : (2 - poisson) * 2 * (1 + poisson) / youngs;
}

} // namespace

HertzMindlin::Coeffs HertzMindlin::mix(double e1, double nu1, double e2, double nu2,
                                       double restitution, double friction) {
  const double ce = compliance(e1, nu1) + compliance(e2, nu2);
  const double cg = shear_compliance(e1, nu1) + shear_compliance(e2, nu2);
  if (!(ce > 0) || !(cg > 0)) throw std::invalid_argument("both materials are rigid");
  Coeffs c;
  c.e_star = 1 / ce;
  c.g_star = 1 / cg;
  c.restitution = restitution;
  c.friction = friction;
  const double le = std::log(restitution);
  c.beta = restitution > 0 ? le / std::sqrt(le * le + pi * pi) : -1.0;
  return c;
}

HertzMindlin::Coeffs ModelScene<HertzMindlin>::example() {
  using namespace example_units;
  const double youngs = 2 * e_star * (1 - poisson * poisson); // E of each of two equal grains
  return HertzMindlin::mix(youngs, poisson, youngs, poisson, restitution, friction);
}

double HertzMindlin::contact_time(const Coeffs& c, double m_eff, double r_eff, double v) {
  const double delta_max = std::pow(15 * m_eff * v * v / (16 * c.e_star * std::sqrt(r_eff)), 0.4);
  return 2.94328 * delta_max / v;
}

} // namespace yuxi
