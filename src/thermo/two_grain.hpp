// The exact two-grain collision of the thermodynamic contact law (Jiang & Liu, Acta Phys. Sin. 67,
// 044502 (2018)), in the paper's own setting: two grains in 2-D, no rotation, head-on or oblique.
// The model is the reconstruction of docs/models/thermodynamic-contact.md (the paper's displayed
// equations are lost); equation numbers and status labels ([TEXT], [RECON-H], [RECON-M], [RECON-L],
// [EXT]) are that document's, and the numbers of its reference model REF are not the paper's.
//
// The ODEs (28)-(33) are integrated by Boost.Odeint's Dormand-Prince 5(4) with dense output to a
// tight tolerance; contact start, separation and the stick/slip switches of the yield condition
// (41) are located on the dense output. The yield condition is the lambda_Y -> infinity limit:
// while sliding, u_t stays on the boundary |u_t| = sqrt(2 xi)(-u_n) of (35) and the work of the
// yield flow goes to heat. The result serves as the reference for the DEM contact model.
#pragma once

#include "contact/thermodynamic_law.hpp"

#include <functional>
#include <limits>
#include <vector>

namespace yuxi::thermo {

// The variables every transport coefficient may depend on [TEXT]: overlap delta [m], spring
// deformations u_n, u_t [m] and relaxation energy w_R [J].
struct ContactVariables {
  double delta, un, ut, w_relax;
};

// One transport coefficient as a function of the contact variables; an empty one is zero.
using Coefficient = std::function<double(const ContactVariables&)>;

// The transport coefficients of the Onsager closure (22)-(26) [RECON-H]. Every one is >= 0.
// Channel "heat" (superscript T) dissipates straight into heat; channel "relax" (superscript R)
// fills the buffer w_R, which decays into heat at the rate w_R / tau. With a sharp step
// (TwoGrainSetup::epsilon = 0) the coefficients are asked for their values just inside the
// contact, at delta = max(delta, d * DBL_MIN), from touching to separation.
struct Transport {
  Coefficient gear_n, gear_t;                // G = 1 - alpha, the gearbox (required) [-]
  Coefficient eta_n_heat, eta_n_relax;       // normal viscosity eta_n^T, eta_n^R [kg/s]
  Coefficient eta_t_heat, eta_t_relax;       // tangential viscosity eta_t^T, eta_t^R [kg/s]
  Coefficient lambda_n_heat, lambda_n_relax; // normal relaxation lambda_n^T, lambda_n^R [m/(N s)]
  Coefficient lambda_t_heat, lambda_t_relax; // tangential relaxation lambda_t^T, lambda_t^R
  double tau = std::numeric_limits<double>::infinity(); // decay time of w_R (22) [s]

  // The bare switch G_n = G_t = Theta_eps(delta/d), no dissipation: Hertz with a Mindlin-like
  // tangential spring.
  static Transport elastic(double d, double epsilon = 0);
  // The example model (37)-(41) (REF, E1, ...) for a contact of stiffness k, reduced mass m_eff
  // and size d = a_1 + a_2. The yield coefficient (41) is not a transport coefficient here:
  // TwoGrainSetup::yield applies it as the lambda_Y -> infinity limit.
  static Transport example(const ExampleModel& p, double k, double m_eff, double d);
};

struct TwoGrainSetup {
  double m1 = 1, m2 = 1, a1 = 0.5, a2 = 0.5; // masses [kg], radii [m]
  double k = 1, xi = 8;                      // elastic constants of (19) [N/m^{3/2}], [-]
  double v0 = 1e-3;            // each grain moves at +-v0 toward the other; impact speed 2 v0
  double impact_parameter = 0; // offset of the centres across the velocities, in units of d
  double epsilon = 0;          // width of the Heaviside in the coefficients (0: sharp step)
  double tail_widths = 30;     // with epsilon > 0: the contact spans delta > -tail_widths eps d
  Transport transport = Transport::elastic(1.0); // for d = 1
  bool yield = true;           // (41) as the lambda_Y -> infinity limit, released energy to heat
  double rel_tol = 1e-12;      // relative tolerance of the integrator
  double abs_tol = 1e-12;      // absolute tolerance, in units of the natural scales: the Hertz
                               // overlap at the impact speed, the impact speed, its energy
  double after_separation = 0; // integrate this long after separation (w_R decays) [s]
  double sample_interval = 0;  // time between samples [s]; 0: no time series

  // The example model p (REF by default) with k = 1 and the default grains; xi and epsilon from p.
  static TwoGrainSetup example(const ExampleModel& p, double v0, double impact_parameter = 0);
};

// One point of the time series. Energies in J; kinetic includes the centre-of-mass motion.
struct Sample {
  double t, x1, y1, x2, y2, delta, fn, ft, un, ut, w_el, kinetic, mechanical, w_relax, heat, total;
};

struct TwoGrainResult {
  // -(v.n at separation)/(v.n at impact) with the normal of the centres at either moment; impact
  // is touching (sharp step) or the start of the soft tail, separation the end of either.
  double restitution;
  // (v.t at separation)/(v.t at impact), same moments: 1 without friction; NaN head-on.
  double tangential_restitution;
  double contact_time;                          // time with delta > 0 [s] (NaN: never)
  double peak_force, max_overlap, peak_w_relax; // [N], [m], [J]
  double initial_energy;                        // E_total at the start [J]
  double final_heat, final_w_relax;             // at the end of the run [J]
  double yield_heat;          // the part of final_heat released by the yield limit (41) [J]
  double max_energy_error;    // max |E_total - E_total(0)| / E_total(0) over the run
  double max_mechanical_rise; // largest increase of E_mech from one step to the next [J]
  double min_w_relax;         // smallest w_R seen [J]
  bool heat_monotone;         // Q never decreased (beyond round-off) from step to step
  double max_yield_ratio;     // max |u_t| / (sqrt(2 xi)(-u_n)) at the steps, u_n < 0
  int slip_phases;            // number of times the contact started to slide
  int steps;                  // accepted integrator steps
  std::vector<Sample> series;
};

// Integrates one collision from contact (or the start of the soft tail) to separation, and on for
// s.after_separation. Throws std::invalid_argument for a setup that cannot collide, and
// std::runtime_error if the grains do not separate or the state becomes non-finite.
TwoGrainResult collide(const TwoGrainSetup& s);

} // namespace yuxi::thermo
