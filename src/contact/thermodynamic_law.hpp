// The thermodynamic (GSH-type) contact law of Jiang & Liu, Acta Phys. Sin. 67, 044502 (2018):
// the pieces shared by the exact two-grain solver and the DEM contact model. Equation numbers
// (19)-(42) and the status labels [RECON-H], [RECON-M], [RECON-L], [EXT] are those of
// docs/models/thermodynamic-contact.md: the paper's displayed equations are lost, so every
// formula here is a reconstruction, and the reference parameter set REF (section 6.3) is not the
// paper's own.
//
// Variables: u_n <= 0 and u_t are the normal and tangential spring deformations, independent
// state variables evolved by (30)-(31), not functions of the overlap [TEXT]; w_R >= 0 is the
// relaxation energy, a buffer between mechanical energy and heat (the "two-stage irreversibility").
#pragma once

#include "core/host_device.hpp"
#include "core/portable_math.hpp"

#include <algorithm>
#include <cmath>

namespace yuxi::thermo {

// Elastic energy (19) [RECON-H], c = 0: w = k (-u_n)^{1/2} ((2/5) u_n^2 + u_t^2 / xi) [J],
// k in N/m^{3/2}, xi dimensionless; ut2 = |u_t|^2.
YUXI_HD inline double elastic_energy(double k, double xi, double un, double ut2) {
  const double x = std::max(-un, 0.0);
  return k * std::sqrt(x) * (0.4 * x * x + ut2 / xi);
}

// Normal spring force (20) [RECON-H]: pi_n = -dw/du_n = k ((-u_n)^{3/2} + u_t^2 / (2 xi
// (-u_n)^{1/2})). Inside the stable region (35) u_t = 0 whenever u_n = 0, so the second term is
// taken as 0 there.
YUXI_HD inline double normal_spring_force(double k, double xi, double un, double ut2) {
  const double x = std::max(-un, 0.0);
  if (x == 0.0) return 0.0;
  const double root = std::sqrt(x);
  return k * (x * root + ut2 / (2 * xi * root));
}

// Tangential stiffness in (21) [RECON-H]: pi_t = -dw/du_t = -kappa u_t, kappa =
// (2k/xi)(-u_n)^{1/2}.
YUXI_HD inline double tangential_stiffness(double k, double xi, double un) {
  return 2 * k / xi * std::sqrt(std::max(-un, 0.0));
}

// Stability (yield) limit (35) [RECON-H]: w is convex iff |u_t| <= sqrt(2 xi) (-u_n), the same
// as the Coulomb condition (36) |pi_t| <= sqrt(2/xi) pi_n, i.e. a friction coefficient sqrt(2/xi).
YUXI_HD inline double yield_limit(double xi, double un) {
  return std::sqrt(2 * xi) * std::max(-un, 0.0);
}

// The friction coefficient the energy implies (36) and its inverse, xi = 2 / mu^2.
YUXI_HD inline double friction_of(double xi) {
  return std::sqrt(2 / xi);
}
YUXI_HD inline double xi_of_friction(double mu) {
  return 2 / (mu * mu);
}

// Smoothed Heaviside (42) [RECON-M]: Theta_eps(x) = (1 + tanh(x/eps))/2; eps = 0 is the sharp step.
YUXI_HD inline double heaviside(double x, double eps) {
  if (eps <= 0) return x > 0 ? 1.0 : 0.0;
  return 0.5 * (1 + std::tanh(x / eps));
}

// Its primitive Phi(delta) = integral_{-inf}^{delta} Theta_eps(s/d) ds = (eps d/2) ln(1 + e^{2
// delta/(eps d)}) (section 5): with G = Theta and lambda_n = 0, u_n = -Phi(delta) exactly. Written
// to avoid overflow: Phi = max(delta, 0) + (eps d/2) ln(1 + e^{-2|delta|/(eps d)}).
YUXI_HD inline double heaviside_primitive(double delta, double d, double eps) {
  if (eps <= 0) return std::max(delta, 0.0);
  const double w = eps * d;
  return std::max(delta, 0.0) + 0.5 * w * std::log1p(std::exp(-2 * std::abs(delta) / w));
}

// Natural units of a contact (section 6.3): reference mass m = 2 m*, size d = a_1 + a_2,
// time t0 = sqrt(m / (k d^{1/2})). The example model's dimensionless numbers are given in them.
struct Scales {
  double mass, size, time;
  YUXI_HD static Scales of(double k, double m_eff, double d) {
    const double m = 2 * m_eff;
    return {m, d, std::sqrt(m / (k * std::sqrt(d)))};
  }
};

// The example model (37)-(41) in dimensionless numbers: REF of section 6.3 by default.
//   (38) G_n = G_t = gear * Theta(delta/d)                       (gear = 1: the paper's switch)
//   (39) eta_n = eta_t = eta_hat sqrt(m k d^{1/2}) Theta(delta/d) (delta/d)^eta_power
//        eta_power = 1/2 is REF's Kuwabara-Kono viscosity [RECON-L, our choice]; 0 is E1, the
//        literal reading, whose restitution grows with impact speed; the viscosity feeds w_R
//        (the relaxation channel) or, with viscosity_to_heat, heat directly.
//   (40) lambda_t = Lambda sqrt(w_R) [RECON-M], Lambda = lambda_hat / (k d^{1/2} t0 sqrt(k
//   d^{5/2})) (41) yield by return mapping (the lambda_Y -> infinity limit) [EXT], released energy
//   -> heat (22) w_R decays into heat at the rate w_R / tau, tau = tau_hat t0.
struct ExampleModel {
  double xi = 8.0;        // friction mu = sqrt(2/xi) = 0.5
  double gear = 1.0;      // G inside the contact
  double eta_hat = 0.3;   // viscosity prefactor
  double eta_power = 0.5; // overlap exponent of the viscosity
  double lambda_hat = 10; // tangential relaxation by w_R (0 switches it off)
  double tau_hat = 5;     // decay time of w_R in units of t0
  double epsilon = 0;     // width of the smoothed Heaviside (0: sharp)
  bool viscosity_to_heat = false;

  YUXI_HD static ExampleModel ref() { return {}; }
  YUXI_HD static ExampleModel e1(double eta_hat) {
    ExampleModel m;
    m.eta_hat = eta_hat;
    m.eta_power = 0;
    return m;
  }
};

// The dimensional coefficients of the example model for one contact (k, m*, d given).
struct ExampleCoefficients {
  double k, xi, gear, eta_scale, eta_power, lambda, tau, d, epsilon;
  bool viscosity_to_heat;

  YUXI_HD static ExampleCoefficients of(const ExampleModel& p, double k, double m_eff, double d) {
    const Scales s = Scales::of(k, m_eff, d);
    const double root_d = std::sqrt(d);
    return {k,
            p.xi,
            p.gear,
            p.eta_hat * std::sqrt(s.mass * k * root_d),
            p.eta_power,
            p.lambda_hat / (k * root_d * s.time * std::sqrt(k * d * d * root_d)),
            p.tau_hat * s.time,
            d,
            p.epsilon,
            p.viscosity_to_heat};
  }
  YUXI_HD double gearbox(double delta) const { return gear * heaviside(delta / d, epsilon); }
  YUXI_HD double viscosity(double delta) const {
    const double on = heaviside(delta / d, epsilon);
    if (on == 0.0) return 0.0;
    return eta_scale * on *
           (eta_power == 0 ? 1.0 : portable::pow(std::max(delta, 0.0) / d, eta_power));
  }
  YUXI_HD double relaxation_rate(double w_relax) const {
    return lambda * std::sqrt(std::max(w_relax, 0.0));
  }
};

} // namespace yuxi::thermo
