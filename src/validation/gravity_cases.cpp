// One or two spheres under gravity: docs/models/validation.md L3 (MFiX DEM01), L4 (DEM02),
// L5 (DEM03), L9 (DEM04, slip to roll) and L10 (sphere on an incline).
#include "core/units.hpp"
#include "validation/impact_probe.hpp"
#include "validation/validation_case.hpp"

#include <cmath>
#include <fmt/format.h>

namespace yuxi::validation {
namespace {

constexpr double g_mfix = 9.80665;

// Damping rate that gives restitution e for a linear spring k and effective mass m:
// gamma = 2 sqrt(k/m) |ln e| / sqrt(pi^2 + ln^2 e)  (docs/models/validation.md L1, inverse).
double gamma_for(double e, double k, double m) {
  if (e >= 1) return 0.0;
  const double le = std::log(e);
  return 2 * std::sqrt(k / m) * -le / std::sqrt(pi * pi + le * le);
}

// L3: a sphere (d = 0.2 m, rho = 2600) falls from 0.5 m onto a wall; gravity acts during the
// contact, so the rebound differs from e (Garg et al. 2012, eqs. 54-63; MFiX DEM01 table).
CaseResult mfix_dem01(const Paths&) {
  CaseResult res;
  const double r = 0.1, m = 10.890855;
  struct Row {
    double k, e, t_rebound, v_rebound, overlap;
  };
  for (const Row& row : {Row{1e4, 0.9, 0.39743489, 2.4754432, 0.098376},
                         Row{1e4, 0.6, 0.40134586, 1.4917362, 0.081951},
                         Row{1e5, 0.8, 0.31934808, 2.2137952, 0.027226},
                         Row{1e5, 1.0, 0.31916510, 2.8009498, 0.030318}}) {
    Impact s;
    const double t_c = pi / std::sqrt(row.k / m);
    s.dt = t_c / 2000;
    s.gravity = {0, 0, -g_mfix};
    s.law = linear_law({row.k, 0, gamma_for(row.e, row.k, m), 0, 0, 0}, 1);
    s.bodies.push_back({{0, 0, 0.5}, {}, {}, r, m});
    s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 0));
    Simulation sim = make_simulation(s);
    double t_end = -1, v_end = 0, max_overlap = 0;
    bool touched = false;
    while (sim.time() < 1.0) {
      sim.step();
      const double overlap = r - sim.particles().x[0].z;
      max_overlap = std::max(max_overlap, overlap);
      if (overlap > 0) touched = true;
      if (touched && overlap <= 0) {
        // interpolate the moment the centre passes height r again
        const double z = sim.particles().x[0].z, vz = sim.particles().v[0].z;
        t_end = sim.time() - (z - r) / vz;
        v_end = vz;
        break;
      }
    }
    const std::string tag = fmt::format("k = {:g}, e = {}", row.k, row.e);
    res.add(tag + ": rebound time [s]", row.t_rebound, t_end, 2 * s.dt);
    res.add_relative(tag + ": rebound speed [m/s]", row.v_rebound, v_end, 2e-3);
    res.add_relative(tag + ": largest overlap [m]", row.overlap, max_overlap, 2e-3);
  }
  return res;
}

// Apex heights of a sphere bouncing on a wall, for n bounces.
std::vector<double> apexes(double k, double e, int n) {
  const double r = 0.1, m = 10.890855;
  Impact s;
  s.dt = pi / std::sqrt(k / m) / 100;
  s.gravity = {0, 0, -g_mfix};
  s.law = linear_law({k, 0, gamma_for(e, k, m), 0, 0, 0}, 1);
  s.bodies.push_back({{0, 0, 0.5}, {}, {}, r, m});
  s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 0));
  Simulation sim = make_simulation(s);
  std::vector<double> out;
  double prev_v = 0;
  while (static_cast<int>(out.size()) < n && sim.time() < 30) {
    sim.step();
    const double v = sim.particles().v[0].z;
    if (prev_v > 0 && v <= 0) {
      // apex between two steps: z + v^2 / 2g from the step before is exact under gravity alone
      out.push_back(sim.particles().x[0].z + v * v / (2 * g_mfix));
    }
    prev_v = v;
  }
  return out;
}

// L4: repeated bounces. e = 1: the apex stays at 0.5 m (MFiX: within 0.1 %); e = 0.9: the
// hard-sphere limit h_n = r + e^2n (h0 - r) is approached as k grows.
CaseResult mfix_dem02(const Paths&) {
  CaseResult res;
  const auto elastic = apexes(5e6, 1.0, 16);
  for (std::size_t b = 0; b < elastic.size(); b += 5)
    res.add_relative(fmt::format("e = 1, apex {} [m]", b + 1), 0.5, elastic[b], 1e-3);
  res.add_relative("e = 1, apex 16 [m]", 0.5, elastic.empty() ? 0 : elastic.back(), 1e-3);
  const auto stiff = apexes(5e6, 0.9, 3), soft = apexes(5e4, 0.9, 3);
  for (int b = 0; b < 3; ++b) {
    const double hard = 0.1 + std::pow(0.9, 2 * (b + 1)) * 0.4;
    res.add_relative(fmt::format("e = 0.9, k = 5e6, apex {} vs hard spheres [m]", b + 1), hard,
                     stiff[static_cast<std::size_t>(b)], 0.005 * (b + 1));
  }
  res.add("soft spring deviates more than stiff (1 = yes)", 1.0,
          std::abs(soft[2] - (0.1 + std::pow(0.9, 6) * 0.4)) >
                  std::abs(stiff[2] - (0.1 + std::pow(0.9, 6) * 0.4))
              ? 1.0
              : 0.0,
          0.0);
  return res;
}

// L5: two spheres stacked between walls 1.8 mm apart, squeezed; they settle to the static
// equilibrium y1 = 4.33247754e-4 m, y2 = 1.36659820e-3 m (MFiX DEM03, exact).
CaseResult mfix_dem03(const Paths&) {
  CaseResult res;
  const double r = 5e-4, m1 = 1.047198e-5, m2 = 5.235988e-6, k = 1000.0, e = 0.5;
  // materials: 0 = lower sphere, 1 = upper sphere, 2 = walls; damping per contact from e with
  // the contact's effective mass.
  ContactLaw<LinearSpringDashpot> law{PairTable<LinearSpringDashpot::Coeffs>(3)};
  law.coeffs.set(0, 2, {k, 0, gamma_for(e, k, m1), 0, 0, 0});
  law.coeffs.set(1, 2, {k, 0, gamma_for(e, k, m2), 0, 0, 0});
  law.coeffs.set(0, 1, {k, 0, gamma_for(e, k, m1 * m2 / (m1 + m2)), 0, 0, 0});
  law.coeffs.set(0, 0, {k, 0, 0, 0, 0, 0});
  law.coeffs.set(1, 1, {k, 0, 0, 0, 0, 0});
  Impact s;
  s.dt = pi / std::sqrt(k / m2) / 200;
  s.gravity = {0, 0, -g_mfix};
  s.law = law;
  s.bodies.push_back({{0, 0, 0.45e-3}, {}, {}, r, m1, 0});
  s.bodies.push_back({{0, 0, 1.35e-3}, {}, {}, r, m2, 1});
  s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 2));
  s.planes.push_back(flat_wall({0, 0, 1.8e-3}, {0, 0, -1}, 2));
  Simulation sim = make_simulation(s);
  sim.run(std::llround(0.05 / s.dt));
  const auto& p = sim.particles();
  const std::size_t lower = p.gid[0] == 0 ? 0 : 1;
  res.add_relative("y1 at rest [m]", 4.33247754e-4, p.x[lower].z, 1e-6);
  res.add_relative("y2 at rest [m]", 1.36659820e-3, p.x[1 - lower].z, 1e-6);
  return res;
}

// A sphere (R = 1, m = 1) at rest on a level plane at its static overlap, gravity tilted by
// theta about y (downhill +x), launched downhill at v0 with no spin.
Simulation incline(double theta_deg, double mu_s, double mu_d, double v0, double gamma_t) {
  const double th = theta_deg * pi / 180, k = 1e5;
  Impact s;
  s.dt = 0.02 * pi / std::sqrt(k);
  s.gravity = {std::sin(th), 0, -std::cos(th)};
  // gamma_n settles the normal motion; gamma_t = 0 where the sphere slides (friction exactly
  // mu_d |F_n|), near critical where it rolls (the spring, loaded at release, must not
  // overshoot the static limit).
  s.law = linear_law({k, 2.0 / 7.0 * k, 30.0, gamma_t, mu_s, mu_d}, 1);
  s.bodies.push_back({{0, 0, 1.0 - std::cos(th) / k}, {v0, 0, 0}, {}, 1.0, 1.0});
  s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 0));
  return make_simulation(s);
}

// Downhill acceleration: least-squares slope of v(t) over 1 <= t <= 2.
double acceleration(Simulation& sim) {
  sim.run(std::llround(1.0 / sim.config().dt));
  double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
  while (sim.time() < 2.0) {
    sim.step();
    const double t = sim.time(), v = sim.particles().v[0].x;
    n += 1, st += t, sv += v, stt += t * t, stv += t * v;
  }
  return (n * stv - st * sv) / (n * stt - st * st);
}

// L9: slip stops at t_s = 2 v0 / (7 mu_d g), then rolling at v = R w = (5/7) v0.
CaseResult slip_to_roll(const Paths&) {
  CaseResult res;
  const double v0 = 1.0, mu_d = 0.3, t_s = 2 * v0 / (7 * mu_d);
  for (double gamma_t : {0.0, 150.0}) {
    Simulation sim = incline(0.0, 0.5, mu_d, v0, gamma_t);
    double t_stop = -1;
    while (sim.time() < 3 * t_s) {
      sim.step();
      const double slip = sim.particles().v[0].x - sim.particles().w[0].y;
      if (t_stop < 0 && slip < 1e-6) t_stop = sim.time();
    }
    if (gamma_t == 0) {
      res.add_relative("slip stops at t_s = 2 v0/(7 mu_d g)", t_s, t_stop, 0.01);
    } else { // tangential damping changes t_s but not the final state; it calms the spring
      res.add_relative("v_f / v0", 5.0 / 7.0, sim.particles().v[0].x / v0, 1e-3);
      res.add_relative("R w_f / v0", 5.0 / 7.0, sim.particles().w[0].y / v0, 1e-3);
    }
  }
  return res;
}

// L10: rolls at (5/7) g sin(theta) when tan(theta) <= 3.5 mu_s, slides at
// g (sin - mu_d cos) above; in 3.5 mu_d < tan(theta) <= 3.5 mu_s it rolls from rest but keeps
// sliding when launched with slip.
CaseResult incline_cases(const Paths&) {
  CaseResult res;
  auto rolling = [](double th) { return 5.0 / 7.0 * std::sin(th); };
  auto sliding = [](double th) { return std::sin(th) - 0.3 * std::cos(th); };
  const double band = std::atan(1.4);
  {
    Simulation sim = incline(20.0, 0.5, 0.3, 0.0, 150.0);
    res.add_relative("20 deg (tan < 3.5 mu_s): a, rolling", rolling(20 * pi / 180),
                     acceleration(sim), 1e-3);
  }
  {
    Simulation sim = incline(65.0, 0.5, 0.3, 0.0, 0.0);
    res.add_relative("65 deg (tan > 3.5 mu_s): a, sliding", sliding(65 * pi / 180),
                     acceleration(sim), 1e-3);
  }
  {
    Simulation sim = incline(band * 180 / pi, 0.5, 0.3, 0.0, 150.0);
    res.add_relative("tan = 1.4 from rest: a, rolling", rolling(band), acceleration(sim), 1e-3);
  }
  {
    Simulation sim = incline(band * 180 / pi, 0.5, 0.3, 2.0, 0.0);
    res.add_relative("tan = 1.4 launched with slip: a, sliding", sliding(band), acceleration(sim),
                     1e-3);
  }
  return res;
}

} // namespace

std::vector<Case> gravity_cases() {
  return {
      {"L3", "MFiX DEM01: free fall, contact under gravity, rebound",
       "Garg et al., MFiX-DEM documentation (2012) eqs. 54-63; MFiX tests/dem/DEM01", false,
       mfix_dem01},
      {"L4", "MFiX DEM02: repeated bounces vs the hard-sphere limit",
       "analytic h_n = r + e^2n (h0 - r); MFiX tests/dem/DEM02", false, mfix_dem02},
      {"L5", "MFiX DEM03: two stacked spheres squeezed between walls", "static equilibrium", false,
       mfix_dem03},
      {"L9", "slip to roll on a level plane (MFiX DEM04)", "analytic", false, slip_to_roll},
      {"L10", "sphere on an incline: rolling, sliding, the mu_s/mu_d band", "analytic", false,
       incline_cases},
  };
}

} // namespace yuxi::validation
