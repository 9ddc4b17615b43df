// Rolling resistance: a torque that opposes the relative rolling of two surfaces in contact,
// standing in for the asymmetric pressure of real, non-spherical or rough contacts. The two
// models of Ai, Chen, Rotter & Ooi (Powder Technol. 206 (2011) 269), docs/models/rolling.md:
//
//  elastic_plastic (their model C, LIGGGHTS "epsd", EDEM "type C"): a spring-dashpot-slider on
//    the rolling displacement u_r = -R* n x (w_i - w_j) (frictional_spring.hpp): the force
//    F_r = -k_r s_r - eta_r u_r, capped at mu_r |F_n|, turns into the torque R* n x F_r on i
//    and its opposite on j. At rest it holds a torque up to mu_r R* |F_n| (a ball on a slope up
//    to tan(theta) = mu_r); rolling, it resists with that torque.
//  constant_torque (their model A, EDEM "CDT"): the torque -mu_r R* |F_n| w_r / |w_r| on i and
//    its opposite on j, w_r = (w_i - w_j) less its component along n: the same resisting torque
//    whenever the surfaces roll on each other, none at rest. A sphere rolling without slip on a
//    plane then decelerates at (5/7) mu_r g and stops after 7 v0^2 / (10 mu_r g).
#pragma once

#include "contact/contact_geometry.hpp"
#include "contact/frictional_spring.hpp"
#include "core/always_inline.hpp"
#include "core/vec3.hpp"

#include <cmath>
#include <cstdint>

namespace yuxi {

enum class RollingModel : std::uint8_t { elastic_plastic, constant_torque };

struct RollingTorque {
  Vec3 torque;             // on i; -torque on j [force length]
  double dissipated = 0.0; // this step [energy]
};

// The constant-torque model: mu_r R* |F_n| against the relative rolling. Its work this step,
// |torque| |w_r| dt, is dissipated.
YUXI_HD inline RollingTorque constant_rolling_torque(const ContactGeometry& g, double normal_force,
                                                     double mu_r) {
  RollingTorque r;
  const Vec3 w = g.w_i - g.w_j;
  const Vec3 w_r = w - dot(w, g.n) * g.n;
  const double rate = norm(w_r);
  if (!(rate > 0.0) || mu_r == 0.0) return r;
  const double magnitude = mu_r * g.r_eff * std::abs(normal_force);
  r.torque = w_r * (-magnitude / rate);
  r.dissipated = magnitude * rate * g.dt;
  return r;
}

// Adds a contact's rolling resistance to `r` under `model`: the constant torque of mu_r R* |fn|,
// or the elastic-plastic slider `law` on u_r = -R* n x (w_i - w_j) (its spring in `spring`),
// which resists up to its friction coefficients times |pressing|. The torque R* n x F_r acts on
// i, its opposite on j; the slider's stored energy joins r.elastic.
YUXI_ALWAYS_INLINE YUXI_HD void add_rolling_resistance(ContactResult& r, const ContactGeometry& g,
                                                       RollingModel model, double mu_r, double fn,
                                                       const SliderLaw& law, double pressing,
                                                       SliderState& spring) {
  if (model == RollingModel::constant_torque) {
    const RollingTorque rr = constant_rolling_torque(g, fn, mu_r);
    r.torque_i += rr.torque;
    r.torque_j -= rr.torque;
    r.dissipated += rr.dissipated;
    return;
  }
  const Vec3 u_r = -g.r_eff * cross(g.n, g.w_i - g.w_j);
  const SliderResult rr =
      slide(spring, carry_in_plane(spring.spring, g.n), u_r, pressing, law, g.dt);
  const Vec3 torque = g.r_eff * cross(g.n, rr.force);
  r.torque_i += torque;
  r.torque_j -= torque;
  r.elastic += spring.stored();
  r.dissipated += rr.dissipated;
}

} // namespace yuxi
