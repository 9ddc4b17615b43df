#include "contact/hertz_mindlin.hpp"

#include "contact/example_units.hpp"
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

const double sqrt_5_6 = std::sqrt(5.0 / 6.0);

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

HertzMindlin::Coeffs HertzMindlin::example() {
  using namespace example_units;
  const double youngs = 2 * e_star * (1 - poisson * poisson); // E of each of two equal grains
  return mix(youngs, poisson, youngs, poisson, restitution, friction);
}

double HertzMindlin::contact_time(const Coeffs& c, double m_eff, double r_eff, double v) {
  const double delta_max = std::pow(15 * m_eff * v * v / (16 * c.e_star * std::sqrt(r_eff)), 0.4);
  return 2.94328 * delta_max / v;
}

ContactResult HertzMindlin::evaluate(const ContactGeometry& g, const Coeffs& c, State& s) {
  ContactResult r;
  r.touching = true;
  const auto [vn, vt] = split_contact_velocity(g);

  const double root = std::sqrt(g.r_eff * g.overlap); // sqrt(R* delta)
  const double s_n = 2 * c.e_star * root;             // normal tangent stiffness dF/d(delta)
  const double s_t = 8 * c.g_star * root;             // Mindlin tangential stiffness
  const double eta_n = -2 * sqrt_5_6 * c.beta * std::sqrt(s_n * g.m_eff);
  const double eta_t = -2 * sqrt_5_6 * c.beta * std::sqrt(s_t * g.m_eff);

  const double fn = (4.0 / 3.0) * c.e_star * root * g.overlap - eta_n * vn;
  const SliderLaw tangential{s_t, eta_t, c.friction, c.friction, CapOn::total};
  // No friction while the dashpot pulls the surfaces together (F_n < 0 at the end of an
  // impact): there is no compression to resist sliding.
  const SliderResult t = slide(s.tangential, carry_in_plane(s.tangential.spring, g.n), vt,
                               std::max(fn, 0.0), tangential, g.dt);

  r.add_contact_force(g, fn, t.force);
  r.elastic = 0.4 * (4.0 / 3.0) * c.e_star * root * g.overlap * g.overlap + s.tangential.stored();
  r.dissipated = eta_n * vn * vn * g.dt + t.dissipated;
  if (c.mu_r > 0 && c.rolling_model == RollingModel::constant_torque) {
    const RollingTorque rr = constant_rolling_torque(g, fn, c.mu_r);
    r.torque_i += rr.torque;
    r.torque_j -= rr.torque;
    r.dissipated += rr.dissipated;
  } else if (c.mu_r > 0) {
    // (LIGGGHTS epsd2: the torque stiffness 2.25 mu_r^2 S_n R*^2, as a force on u_r)
    const Vec3 u_r = -g.r_eff * cross(g.n, g.w_i - g.w_j);
    const SliderLaw rolling{2.25 * c.mu_r * c.mu_r * s_n, 0.0, c.mu_r, c.mu_r, CapOn::total};
    const SliderResult rr = slide(s.rolling, carry_in_plane(s.rolling.spring, g.n), u_r,
                                  std::max(fn, 0.0), rolling, g.dt);
    const Vec3 torque = g.r_eff * cross(g.n, rr.force);
    r.torque_i += torque;
    r.torque_j -= torque;
    r.elastic += s.rolling.stored();
    r.dissipated += rr.dissipated;
  }
  return r;
}

double HertzMindlin::release(const Coeffs&, State& s) {
  const double e = yuxi::release(s.tangential) + yuxi::release(s.rolling);
  s = State{};
  return e;
}

} // namespace yuxi
