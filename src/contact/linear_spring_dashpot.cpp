#include "contact/linear_spring_dashpot.hpp"

#include "core/units.hpp"

#include <limits>

namespace yuxi {

double LinearSpringDashpot::contact_time(const Coeffs& c, double m_eff, double, double) {
  const double w2 = c.k_n / m_eff - 0.25 * c.gamma_n * c.gamma_n;
  return w2 > 0 ? pi / std::sqrt(w2) : std::numeric_limits<double>::infinity();
}

ContactResult LinearSpringDashpot::evaluate(const ContactGeometry& g, const Coeffs& c, State& s) {
  ContactResult r;
  r.touching = true;
  const auto [vn, vt] = split_contact_velocity(g);

  const double fn = c.k_n * g.overlap - g.m_eff * c.gamma_n * vn;
  const Vec3 carried = c.carry == Carry::rotate
                           ? carry_in_plane(s.tangential.spring, g.n)
                           : s.tangential.spring - dot(s.tangential.spring, g.n) * g.n;
  const SliderLaw tangential{c.k_t, g.m_eff * c.gamma_t, c.mu_s, c.mu_d, c.friction_cap};
  const SliderResult t = slide(s.tangential, carried, vt, fn, tangential, g.dt);

  r.add_contact_force(g, fn, t.force);
  r.elastic = 0.5 * c.k_n * g.overlap * g.overlap + s.tangential.stored;
  r.dissipated = g.m_eff * c.gamma_n * vn * vn * g.dt + t.dissipated;

  if (c.rolling()) {
    const Vec3 u_r = -g.r_eff * cross(g.n, g.w_i - g.w_j);
    const SliderLaw rolling{c.k_r, g.m_eff * c.gamma_r, c.mu_r, c.mu_r, CapOn::total};
    const SliderResult rr =
        slide(s.rolling, carry_in_plane(s.rolling.spring, g.n), u_r, fn, rolling, g.dt);
    const Vec3 torque = g.r_eff * cross(g.n, rr.force);
    r.torque_i += torque;
    r.torque_j -= torque;
    r.elastic += s.rolling.stored;
    r.dissipated += rr.dissipated;
  }
  return r;
}

double LinearSpringDashpot::release(const Coeffs&, State& s) {
  const double e = yuxi::release(s.tangential) + yuxi::release(s.rolling);
  s = State{};
  return e;
}

} // namespace yuxi
