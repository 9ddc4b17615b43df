#include "contact/linear_spring_dashpot.hpp"

#include "contact/tangent_plane.hpp"
#include "core/units.hpp"

#include <limits>

namespace yuxi {

double LinearSpringDashpot::contact_time(const Coeffs& c, double m_eff, double, double) {
  const double w2 = c.k_n / m_eff - 0.25 * c.gamma_n * c.gamma_n;
  return w2 > 0 ? pi / std::sqrt(w2) : std::numeric_limits<double>::infinity();
}

ContactResult LinearSpringDashpot::evaluate(const ContactGeometry& g, const Coeffs& c, State& s) {
  ContactResult r;
  if (g.overlap <= 0.0) {
    r.dissipated = release(c, s);
    return r;
  }
  r.touching = true;
  const Vec3 vc = g.contact_velocity();
  const double vn = dot(vc, g.n);
  const Vec3 vt = vc - vn * g.n;

  // Normal force: spring + dashpot.
  const double fn = c.k_n * g.overlap - g.m_eff * c.gamma_n * vn;
  const double fn_abs = std::abs(fn);

  // Tangential spring: carry into the current tangent plane, then integrate the slip.
  const Vec3 carried = rotate_into_tangent_plane(s.spring, g.n);
  const Vec3 increment = vt * g.dt;
  Vec3 spring = carried + increment;
  const double trial2 = c.k_t * c.k_t * norm2(spring);
  const double limit = (s.sliding ? c.mu_d : c.mu_s) * fn_abs;
  double slip_loss = 0.0;
  if (trial2 > limit * limit) {
    // Slides: the spring is cut back to the dynamic Coulomb limit. What is lost is the work
    // done into the spring this step, k_t (s_old + s_new)/2 . ds, less the rise of its stored
    // energy: exactly zero while sticking, F u dt in steady sliding, the whole energy drop when
    // a falling normal force lowers the limit.
    spring *= c.mu_d * fn_abs / std::sqrt(trial2);
    slip_loss =
        c.k_t * (dot(0.5 * (carried + spring), increment) - 0.5 * (norm2(spring) - norm2(carried)));
    s.sliding = 1;
  } else {
    s.sliding = 0;
  }
  s.spring = spring;

  const Vec3 f_damp_t = -(g.m_eff * c.gamma_t) * vt;
  const Vec3 f_t = -c.k_t * spring + f_damp_t;
  r.force = fn * g.n + f_t;
  // Torques of the tangential force applied at the contact point: lever arm -a_i n on i,
  // +a_j n on j with the force -F_t there.
  const Vec3 nxf = cross(g.n, f_t);
  r.torque_i = -g.a_i * nxf;
  r.torque_j = -g.a_j * nxf;
  r.elastic = 0.5 * c.k_n * g.overlap * g.overlap + 0.5 * c.k_t * norm2(spring);
  r.dissipated = g.m_eff * (c.gamma_n * vn * vn + c.gamma_t * norm2(vt)) * g.dt + slip_loss;
  return r;
}

double LinearSpringDashpot::release(const Coeffs& c, State& s) {
  const double stored = 0.5 * c.k_t * norm2(s.spring);
  s = State{};
  return stored;
}

} // namespace yuxi
