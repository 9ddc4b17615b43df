#include "contact/luding.hpp"

#include "contact/example_units.hpp"
#include "core/units.hpp"

#include <algorithm>
#include <limits>

namespace yuxi {
namespace {

double unloading_stiffness(const Luding::Coeffs& c, double delta_max, double a12) {
  if (c.kp <= c.k1) return c.k1;
  const double delta_p = c.kp / (c.kp - c.k1) * c.phi_f * 2 * a12;
  return delta_max >= delta_p ? c.kp : c.k1 + (c.kp - c.k1) * delta_max / delta_p;
}

} // namespace

Luding::Coeffs Luding::example() {
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

ContactResult Luding::evaluate(const ContactGeometry& g, const Coeffs& c, State& s) {
  ContactResult r;
  r.touching = true;
  const double delta = g.overlap;
  const double a12 = g.r_eff;

  // Hysteretic normal spring.
  double k2 = unloading_stiffness(c, s.delta_max, a12);
  double delta0 = (1 - c.k1 / k2) * s.delta_max;
  double f_hys = k2 * (delta - delta0);
  if (f_hys >= c.k1 * delta) { // virgin loading
    f_hys = c.k1 * delta;
    s.delta_max = delta;
    k2 = unloading_stiffness(c, delta, a12);
    delta0 = (1 - c.k1 / k2) * delta;
  } else if (f_hys <= -c.kc * delta) { // adhesive limit: move the unloading branch here
    f_hys = -c.kc * delta;
    s.delta_max = (k2 + c.kc) / (k2 - c.k1) * delta;
    delta0 = (1 - c.k1 / k2) * s.delta_max;
  }
  const double stored_n = 0.5 * k2 * (delta - delta0) * (delta - delta0);
  const double work_in = 0.5 * (s.f_hys + f_hys) * (delta - s.delta);
  const double normal_loss = work_in - (stored_n - s.stored_n);
  s.delta = delta;
  s.f_hys = f_hys;
  s.stored_n = stored_n;

  const auto [vn, vt] = split_contact_velocity(g);
  const double fn = f_hys - g.m_eff * c.gamma_n * vn;
  const double pressing = std::max(fn + c.kc * delta, 0.0); // no friction without compression

  const SliderLaw tangential{c.k_t, g.m_eff * c.gamma_t, c.mu_s, c.mu_d, CapOn::total};
  const SliderResult t =
      slide(s.tangential, carry_in_plane(s.tangential.spring, g.n), vt, pressing, tangential, g.dt);
  const Vec3 w_rel = g.w_i - g.w_j;
  const Vec3 u_r = -a12 * cross(g.n, w_rel);
  const SliderLaw rolling{c.k_r, g.m_eff * c.gamma_r, c.mu_r, c.mu_r, CapOn::total};
  const SliderResult rr =
      slide(s.rolling, carry_in_plane(s.rolling.spring, g.n), u_r, pressing, rolling, g.dt);
  const Vec3 u_o = (a12 * dot(w_rel, g.n)) * g.n;
  const SliderLaw torsion{c.k_o, g.m_eff * c.gamma_o, c.mu_o, c.mu_o, CapOn::total};
  const SliderResult tor =
      slide(s.torsion, carry_along(s.torsion.spring, g.n), u_o, pressing, torsion, g.dt);

  r.add_contact_force(g, fn, t.force);
  const Vec3 roll = a12 * cross(g.n, rr.force);
  const Vec3 twist = a12 * tor.force;
  r.torque_i += roll + twist;
  r.torque_j -= roll + twist;
  r.elastic = stored_n + s.tangential.stored() + s.rolling.stored() + s.torsion.stored();
  r.dissipated = g.m_eff * c.gamma_n * vn * vn * g.dt + normal_loss + t.dissipated + rr.dissipated +
                 tor.dissipated;
  return r;
}

double Luding::release(const Coeffs&, State& s) {
  const double e = s.stored_n + yuxi::release(s.tangential) + yuxi::release(s.rolling) +
                   yuxi::release(s.torsion);
  s = State{};
  return e;
}

} // namespace yuxi
