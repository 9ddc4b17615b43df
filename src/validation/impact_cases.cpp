// Binary impacts without gravity: docs/models/validation.md L1, L2, L6, L7, Chung & Ooi (2011)
// Tests 1-8, and the restitution of Luding's hysteretic spring.
#include "core/units.hpp"
#include "validation/impact_probe.hpp"
#include "validation/validation_case.hpp"

#include <cmath>
#include <fmt/format.h>

namespace yuxi::validation {
namespace {

using Linear = LinearSpringDashpot::Coeffs;

double sphere_mass(double r, double density) {
  return 4.0 / 3.0 * pi * r * r * r * density;
}

// L1/L2: head-on, no friction: e = exp(-gamma_n t_c / 2), t_c = pi / sqrt(k/m_eff - gamma^2/4),
// with the attractive dashpot force kept (the clamped variant gives e = 0.885900, L2).
CaseResult head_on(const Paths&) {
  CaseResult res;
  const double k = 2e5, gamma = 50.0, m = 1.0, r = 0.5, v0 = 1.0;
  for (int partner = 0; partner < 3; ++partner) { // grain, wall particle, flat wall
    const double m_eff = partner == 0 ? 0.5 * m : m;
    const double t_c = pi / std::sqrt(k / m_eff - 0.25 * gamma * gamma);
    const double e = std::exp(-0.5 * gamma * t_c);
    Impact s;
    s.dt = t_c / 1000;
    s.law = linear_law({k, 0, gamma, 0, 0, 0}, 1);
    s.bodies.push_back({{0, 0, r + 1e-6}, {0, 0, -v0}, {}, r, m});
    if (partner == 0) s.bodies.push_back({{0, 0, -r - 1e-6}, {0, 0, v0}, {}, r, m});
    if (partner == 1) s.bodies.push_back({{0, 0, -r - 1e-6}, {}, {}, r, m, 0, Kind::wall});
    if (partner == 2) s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 0));
    const auto out = run_impact(s);
    const char* name = partner == 0 ? "grain" : partner == 1 ? "wall particle" : "flat wall";
    res.add_relative(fmt::format("e vs {}", name), e, out.v[0].z / v0, 0.005);
    res.add_relative(fmt::format("t_c vs {}", name), t_c, out.contact_time, 0.005);
  }
  // Silbert et al. (2001) units, m_eff = 0.5: published t_c = 4.97118e-3, e = 0.883133; the
  // clamped variant would give 0.885900 (L2), so 1e-4 pins the unclamped law down.
  // The velocity is sampled at the first step after separation, which costs gamma_n dt of e:
  // t_c/10000 keeps that below 1e-4.
  Impact s;
  s.dt = 4.97118e-3 / 10000;
  s.law = linear_law({2e5, 0, 50.0, 0, 0, 0}, 1);
  s.bodies = {{{0, 0, 0.5}, {0, 0, -0.5}, {}, 0.5, 1.0}, {{0, 0, -0.5}, {0, 0, 0.5}, {}, 0.5, 1.0}};
  const auto out = run_impact(s);
  res.add("e, Silbert units (unclamped, L2)", 0.883133, out.v[0].z / 0.5, 1e-4);
  res.add_relative("t_c, Silbert units", 4.97118e-3, out.contact_time, 0.005);
  return res;
}

// A sphere (R = 1, m = 1, no spin) hitting a flat wall at `theta` degrees from the normal.
ImpactOutcome oblique_on_wall(const Linear& c, double theta, double dt) {
  const double th = theta * pi / 180;
  Impact s;
  s.dt = dt;
  s.law = linear_law(c, 1);
  s.bodies.push_back({{0, 0, 1.0}, {std::sin(th), 0, -std::cos(th)}, {}, 1.0, 1.0});
  s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 0));
  return run_impact(s);
}

// L6: k_t = 2/7 k_n, no damping, full stick: e_t = 3/7, beta = 1, R w' = 10/7 v_t0.
CaseResult oblique_stick(const Paths&) {
  CaseResult res;
  const double k = 1e5, t_c = pi / std::sqrt(k);
  for (double theta : {10.0, 30.0, 45.0}) {
    const auto out = oblique_on_wall({k, 2.0 / 7.0 * k, 0, 0, 1e6, 1e6}, theta, t_c / 400);
    const double vt0 = std::sin(theta * pi / 180), vn0 = std::cos(theta * pi / 180);
    res.add(fmt::format("e_n at {} deg", theta), 1.0, out.v[0].z / vn0, 1e-3);
    res.add(fmt::format("e_t at {} deg", theta), 3.0 / 7.0, out.v[0].x / vt0, 1e-3);
    res.add(fmt::format("R w'/v_t0 at {} deg", theta), 10.0 / 7.0, out.w[0].y / vt0, 1e-3);
    res.add(fmt::format("beta at {} deg", theta), 1.0, -(out.v[0].x - out.w[0].y) / vt0, 2e-3);
  }
  return res;
}

// L7: gross sliding: e_t = 1 - mu (1 + e)/tan(theta), |w'| R = (5/2) mu (1 + e) V cos(theta).
CaseResult oblique_sliding(const Paths&) {
  CaseResult res;
  const double k = 1e5, e = 0.98, mu = 0.092, t_c = pi / std::sqrt(k);
  const double le = std::log(e), gamma = 2 * std::sqrt(k) * -le / std::sqrt(pi * pi + le * le);
  for (double theta : {35.0, 45.0, 60.0, 75.0}) {
    const double th = theta * pi / 180;
    const auto out = oblique_on_wall({k, 2.0 / 7.0 * k, gamma, 0, mu, mu}, theta, t_c / 400);
    res.add_relative(fmt::format("e_t at {} deg", theta), 1 - mu * (1 + e) / std::tan(th),
                     out.v[0].x / std::sin(th), 0.005);
    res.add_relative(fmt::format("|w'| R at {} deg", theta), 2.5 * mu * (1 + e) * std::cos(th),
                     std::abs(out.w[0].y), 0.005);
  }
  return res;
}

// Luding (2008): without damping and adhesion, an impact rebounds with e = sqrt(k1/k2), k2 the
// unloading stiffness: kp once delta_max >= delta_p, else k1 + (kp - k1) delta_max/delta_p;
// delta_max = v0 sqrt(m_eff/k1) (loading on k1).
CaseResult luding_restitution(const Paths&) {
  CaseResult res;
  const double k1 = 1e5, kp = 5e5, m = 1.0, r = 0.5, v0 = 1.0;
  for (double phi_f : {1e-4, 0.05}) {
    Luding::Coeffs c;
    c.k1 = k1;
    c.kp = kp;
    c.phi_f = phi_f;
    ContactLaw<Luding> law{PairTable<Luding::Coeffs>(1)};
    law.coeffs.set(0, 0, c);
    Impact s;
    s.dt = pi / std::sqrt(kp / m) / 2000;
    s.law = law;
    s.bodies.push_back({{0, 0, r + 1e-9}, {0, 0, -v0}, {}, r, m});
    s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 0));
    const auto out = run_impact(s);
    const double delta_max = v0 * std::sqrt(m / k1);
    const double delta_p = kp / (kp - k1) * phi_f * 2 * r;
    const double k2 = delta_max >= delta_p ? kp : k1 + (kp - k1) * delta_max / delta_p;
    res.add_relative(fmt::format("delta_max, phi_f = {}", phi_f), delta_max, out.max_overlap, 2e-3);
    res.add_relative(fmt::format("e = sqrt(k1/k2), phi_f = {}", phi_f), std::sqrt(k1 / k2),
                     out.v[0].z / v0, 2e-3);
  }
  return res;
}

// --- Chung & Ooi (2011), Hertz-Mindlin -------------------------------------------------------

struct MaterialData {
  const char* name;
  double youngs, poisson, density;
};

constexpr double rigid = std::numeric_limits<double>::infinity();

ContactLaw<HertzMindlin> hertz_law(const MaterialData& a, const MaterialData& wall, double e,
                                   double mu) {
  // material 0: the sphere(s), material 1: the partner (another sphere or a rigid plane)
  ContactLaw<HertzMindlin> law{PairTable<HertzMindlin::Coeffs>(2)};
  law.coeffs.set(0, 0, HertzMindlin::mix(a.youngs, a.poisson, a.youngs, a.poisson, e, mu));
  law.coeffs.set(0, 1, HertzMindlin::mix(a.youngs, a.poisson, wall.youngs, wall.poisson, e, mu));
  return law;
}

// Tests 1-2: elastic normal impact; Hertz theory for delta_max, F_max, t_c.
void hertz_elastic(CaseResult& res, const MaterialData& mat, double r, double v_each, bool plane,
                   double delta_max, double f_max, double t_c_us) {
  const double m = sphere_mass(r, mat.density);
  Impact s;
  s.dt = t_c_us * 1e-6 / 400;
  s.law = hertz_law(mat, {"rigid", rigid, 0.3, 1}, 1.0, 0.0);
  s.bodies.push_back({{0, 0, r + 1e-9}, {0, 0, -v_each}, {}, r, m});
  if (plane) {
    s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 1));
  } else {
    s.bodies.push_back({{0, 0, -r - 1e-9}, {0, 0, v_each}, {}, r, m});
  }
  const auto out = run_impact(s);
  res.add_relative(fmt::format("{}: delta_max [um]", mat.name), delta_max, out.max_overlap * 1e6,
                   0.005);
  res.add_relative(fmt::format("{}: F_max [kN]", mat.name), f_max, out.peak_force * 1e-3, 0.005);
  res.add_relative(fmt::format("{}: t_c [us]", mat.name), t_c_us, out.contact_time * 1e6, 0.005);
  res.add(fmt::format("{}: rebound speed / impact speed", mat.name), 1.0, out.v[0].z / v_each,
          1e-3);
}

CaseResult chung_ooi_1(const Paths&) {
  CaseResult res;
  hertz_elastic(res, {"glass", 48e9, 0.20, 2800}, 0.010, 10.0, false, 274.113, 10.6969, 40.340);
  hertz_elastic(res, {"limestone", 20e9, 0.25, 2500}, 0.010, 10.0, false, 368.304, 7.1082, 54.201);
  return res;
}

CaseResult chung_ooi_2(const Paths&) {
  CaseResult res;
  hertz_elastic(res, {"Al alloy", 70e9, 0.30, 2699}, 0.10, 0.2, true, 49.717, 11.3699, 731.66);
  hertz_elastic(res, {"Mg alloy", 40e9, 0.35, 1800}, 0.10, 0.2, true, 52.123, 7.2327, 767.07);
  return res;
}

// A sphere hitting a rigid plane with velocity (v_t, 0, -v_n) and spin w about +y.
ImpactOutcome hertz_on_plane(const MaterialData& mat, double r, double e, double mu, double v_n,
                             double v_t, double w_y, double t_c) {
  Impact s;
  s.dt = t_c / 1000;
  s.law = hertz_law(mat, {"rigid", rigid, 0.3, 1}, e, mu);
  s.bodies.push_back(
      {{0, 0, r + 1e-12}, {v_t, 0, -v_n}, {0, w_y, 0}, r, sphere_mass(r, mat.density)});
  s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 1));
  return run_impact(s);
}

// Test 3: the damping law is calibrated so that e_out = e_in at any speed.
CaseResult chung_ooi_3(const Paths&) {
  CaseResult res;
  for (const auto& [mat, t_c] :
       {std::pair{MaterialData{"Al oxide", 380e9, 0.23, 4000}, 6.1045e-6},
        std::pair{MaterialData{"cast iron", 100e9, 0.25, 7000}, 12.972e-6}})
    for (double e : {0.2, 0.4, 0.6, 0.8, 1.0}) {
      const auto out = hertz_on_plane(mat, 2.5e-3, e, 0.0, 3.9, 0.0, 0.0, t_c);
      res.add_relative(fmt::format("{}: e_out for e_in = {}", mat.name, e), e, out.v[0].z / 3.9,
                       0.01);
    }
  return res;
}

// Test 4: oblique impacts at 3.9 m/s; gross sliding above 32.5 deg is analytic (table of
// docs/models/validation.md); below it the Mindlin stick/slip features of Chung & Ooi's DEM curve.
CaseResult chung_ooi_4(const Paths&) {
  CaseResult res;
  const double e = 0.98, mu = 0.092, v = 3.9, r = 2.5e-3;
  const MaterialData oxide{"Al oxide", 380e9, 0.23, 4000}, alloy{"Al alloy", 70e9, 0.33, 2700};
  struct Row {
    double theta, e_t, w, phi_c;
  };
  const Row rows[] = {{35, 0.7398, 581.95, 3.658},
                      {45, 0.8178, 502.35, 20.296},
                      {60, 0.8948, 355.21, 48.159},
                      {75, 0.9512, 183.87, 72.427},
                      {85, 0.9841, 61.92, 84.812}};
  for (const auto& mat : {oxide, alloy})
    for (const Row& row : rows) {
      const double th = row.theta * pi / 180;
      const auto out = hertz_on_plane(mat, r, e, mu, v * std::cos(th), v * std::sin(th), 0, 6e-6);
      const double u1 = out.v[0].x - r * out.w[0].y; // contact-point tangential velocity
      res.add_relative(fmt::format("{} {} deg: e_t", mat.name, row.theta), row.e_t,
                       out.v[0].x / (v * std::sin(th)), 0.005);
      res.add_relative(fmt::format("{} {} deg: |w'| [rad/s]", mat.name, row.theta), row.w,
                       std::abs(out.w[0].y), 0.005);
      res.add(fmt::format("{} {} deg: phi_c [deg]", mat.name, row.theta), row.phi_c,
              std::atan(u1 / out.v[0].z) * 180 / pi, 0.3);
    }
  // Stick/micro-slip regime, Al oxide (digitized Chung & Ooi curve): e_t minimum ~0.61-0.62
  // near 17-20 deg, phi_c ~ -7.5 deg near 20-25 deg, |w'| ~ 615-635 rad/s near 27-30 deg.
  const auto at = [&](double theta) {
    const double th = theta * pi / 180;
    return hertz_on_plane(oxide, r, e, mu, v * std::cos(th), v * std::sin(th), 0, 6e-6);
  };
  const auto o20 = at(20), o30 = at(30);
  res.add("Al oxide 20 deg: e_t (digitized 0.616)", 0.616,
          o20.v[0].x / (v * std::sin(20 * pi / 180)), 0.02);
  res.add("Al oxide 20 deg: phi_c [deg] (digitized -7.54)", -7.54,
          std::atan((o20.v[0].x - r * o20.w[0].y) / o20.v[0].z) * 180 / pi, 1.5);
  res.add("Al oxide 30 deg: |w'| [rad/s] (digitized 616.5)", 616.5, std::abs(o30.w[0].y), 20.0);
  return res;
}

// Test 5: v_n0 = 5 m/s, sliding branch: psi2 = psi1 - 7, Omega = 5 (normalized spin).
CaseResult chung_ooi_5(const Paths&) {
  CaseResult res;
  const double mu = 0.3, vn = 5.0, r = 1e-5;
  const MaterialData steel{"steel", 208e9, 0.30, 7850};
  for (double vt : {12.0, 15.0, 18.0, 21.0}) {
    const auto out = hertz_on_plane(steel, r, 1.0, mu, vn, vt, 0, 1e-8);
    const double psi1 = vt / (mu * vn);
    const double u1 = out.v[0].x - r * out.w[0].y;
    res.add(fmt::format("steel v_t0 = {}: psi2", vt), psi1 - 7, u1 / (mu * out.v[0].z),
            0.01 * psi1);
    res.add(fmt::format("steel v_t0 = {}: |Omega|", vt), 5.0, r * std::abs(out.w[0].y) / (mu * vn),
            0.05);
  }
  return res;
}

// Test 6: spinning sphere (w0 about y) dropped normally at 0.2 m/s; sliding branch (w0 >= 4.2):
// beta = 4.2/w0 - 1, w' = w0 - 3, |v_t'| = mu (1 + e) v_n0 = 0.12 m/s.
// Test 8 (case B): the same against a free sphere 5 times larger and 125000 times heavier.
// These rigid-body numbers take the friction impulse as mu times the normal impulse. With
// Tsuji's damping (which gives e_out = e_in, Test 3) the normal force turns attractive at the
// end of the impact; no friction acts then, and the compressive impulse exceeds the net one by
// 3.4 % at e = 0.5 (measured), so |v_t'| = 0.124: the rigid-body numbers are checked at 4 %
// (beta at 0.025). What holds exactly for any normal law while the contact slides throughout is
// R (w0 - w') = (5/2) |v_t'|, checked at 1e-3.
void spinning_impacts(CaseResult& res, bool big_partner) {
  const double e = 0.5, mu = 0.4, vn = 0.2, r = 0.1;
  const MaterialData alloy{"Al alloy", 70e9, 0.33, 2700};
  for (double w0 : {6.0, 10.0, 14.0, 21.0}) {
    Impact s;
    s.dt = 5e-7;
    s.bodies.push_back(
        {{0, 0, r + 1e-12}, {0, 0, -vn}, {0, w0, 0}, r, sphere_mass(r, alloy.density)});
    if (big_partner) {
      // material 0 both: same E, nu, G (case B)
      ContactLaw<HertzMindlin> law{PairTable<HertzMindlin::Coeffs>(1)};
      law.coeffs.set(
          0, 0, HertzMindlin::mix(alloy.youngs, alloy.poisson, alloy.youngs, alloy.poisson, e, mu));
      s.law = law;
      s.bodies.push_back(
          {{0, 0, -5 * r - 1e-12}, {}, {}, 5 * r, sphere_mass(5 * r, 1000 * alloy.density)});
    } else {
      s.law = hertz_law(alloy, {"rigid", rigid, 0.3, 1}, e, mu);
      s.planes.push_back(flat_wall({0, 0, 0}, {0, 0, 1}, 1));
    }
    const auto out = run_impact(s);
    const double u0 = -r * w0; // contact point moves along -x for spin +y
    const double u1 = out.v[0].x - r * out.w[0].y;
    const char* what = big_partner ? "large sphere" : "plane";
    res.add(fmt::format("{} w0 = {}: beta", what, w0), 4.2 / w0 - 1, -u1 / u0, 0.025);
    res.add_relative(fmt::format("{} w0 = {}: |v_t'| [m/s]", what, w0), 0.12, std::abs(out.v[0].x),
                     0.04);
    res.add_relative(fmt::format("{} w0 = {}: R (w0 - w') / |v_t'|", what, w0), 2.5,
                     r * (w0 - out.w[0].y) / std::abs(out.v[0].x), 1e-3);
    res.add_relative(fmt::format("{} w0 = {}: v_n'/v_n0", what, w0), e, out.v[0].z / vn, 0.01);
  }
}

CaseResult chung_ooi_6(const Paths&) {
  CaseResult res;
  spinning_impacts(res, false);
  return res;
}

CaseResult chung_ooi_8(const Paths&) {
  CaseResult res;
  spinning_impacts(res, true);
  return res;
}

// Test 7: two equal spheres with equal and opposite spins: the contact points move together,
// so no tangential force may appear: w' = w0, v_y' = 0, v_z' = -/+ e v.
CaseResult chung_ooi_7(const Paths&) {
  CaseResult res;
  const double e = 0.5, mu = 0.4, v = 0.2, r = 0.1;
  for (const MaterialData& mat :
       {MaterialData{"Al alloy", 70e9, 0.33, 2700}, MaterialData{"copper", 120e9, 0.35, 8900}})
    for (double w0 : {0.175, 2.0, 21.0}) {
      Impact s;
      s.dt = 5e-7;
      s.law = hertz_law(mat, mat, e, mu);
      const double m = sphere_mass(r, mat.density);
      s.bodies.push_back({{0, 0, r + 1e-12}, {0, 0, -v}, {w0, 0, 0}, r, m});
      s.bodies.push_back({{0, 0, -r - 1e-12}, {0, 0, v}, {-w0, 0, 0}, r, m});
      const auto out = run_impact(s);
      res.add(fmt::format("{} w0 = {}: w'/w0", mat.name, w0), 1.0, out.w[0].x / w0, 1e-9);
      res.add(fmt::format("{} w0 = {}: v_y' [m/s]", mat.name, w0), 0.0, out.v[0].y, 1e-12);
      res.add(fmt::format("{} w0 = {}: v_z'/v", mat.name, w0), e, out.v[0].z / v, 0.01);
    }
  return res;
}

} // namespace

std::vector<Case> impact_cases() {
  return {
      {"L1", "head-on linear spring-dashpot: restitution and contact time (and L2: unclamped)",
       "analytic; Silbert et al. PRE 64 (2001); Schwager & Poschel, Granular Matter 9 (2007)",
       false, head_on},
      {"L6", "oblique impact, k_t = 2/7 k_n, full stick: e_t = 3/7",
       "analytic; Schwager, Becker & Poschel, PRE 77 (2008)", false, oblique_stick},
      {"L7", "oblique impact, gross sliding", "analytic rigid-body Coulomb impact", false,
       oblique_sliding},
      {"LUD", "Luding hysteretic spring: e = sqrt(k1/k2)", "Luding, Granular Matter 10 (2008)",
       false, luding_restitution},
      {"CO1", "Chung & Ooi Test 1: elastic sphere-sphere impact (Hertz)",
       "Hertz theory; Chung & Ooi, Granular Matter 13 (2011)", false, chung_ooi_1},
      {"CO2", "Chung & Ooi Test 2: elastic sphere-plane impact (Hertz)", "Hertz theory", false,
       chung_ooi_2},
      {"CO3", "Chung & Ooi Test 3: restitution on a plane", "input e (Tsuji damping)", false,
       chung_ooi_3},
      {"CO4", "Chung & Ooi Test 4: oblique impacts, varying angle",
       "analytic sliding branch; digitized Chung & Ooi DEM curve (Kratos)", false, chung_ooi_4},
      {"CO5", "Chung & Ooi Test 5: oblique impacts, varying tangential speed",
       "analytic sliding branch", false, chung_ooi_5},
      {"CO6", "Chung & Ooi Test 6: spinning sphere on a plane", "analytic sliding branch", false,
       chung_ooi_6},
      {"CO7", "Chung & Ooi Test 7: opposite spins, no tangential force", "analytic", false,
       chung_ooi_7},
      {"CO8", "Chung & Ooi Test 8: spinning sphere on a large heavy sphere (case B)",
       "analytic sliding branch", false, chung_ooi_8},
  };
}

} // namespace yuxi::validation
