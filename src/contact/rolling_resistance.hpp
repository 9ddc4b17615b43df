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

} // namespace yuxi
