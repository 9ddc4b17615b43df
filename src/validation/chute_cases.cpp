// The LAMMPS chute benchmark (docs/models/validation.md section 3): C1, 100 steps of data.chute
// against LAMMPS itself (reference output and the command that made it: tests/validation/data); C2,
// steady flow of a slice of it down a 24 degree incline (Silbert et al. 2001).
#include "analysis/coarse_grain.hpp"
#include "analysis/line_fit.hpp"
#include "core/units.hpp"
#include "io/scene_reader.hpp"
#include "run/coarse_grain_contacts.hpp"
#include "run/scene_builder.hpp"
#include "validation/validation_case.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <zlib.h>

namespace yuxi::validation {
namespace {

// Thermo lines "Step Atoms KinEng c_1 Volume" of the LAMMPS log, by step.
std::unordered_map<long, std::pair<double, double>>
lammps_thermo(const std::filesystem::path& log) {
  std::ifstream in(log);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", log.string()));
  std::unordered_map<long, std::pair<double, double>> out;
  std::string line;
  bool in_table = false;
  while (std::getline(in, line)) {
    if (line.find("Step") != std::string::npos && line.find("KinEng") != std::string::npos) {
      in_table = true;
      continue;
    }
    if (!in_table) continue;
    std::istringstream row(line);
    long step = 0, atoms = 0;
    double ke = 0, erot = 0, vol = 0;
    if (row >> step >> atoms >> ke >> erot >> vol) {
      out.emplace(step, std::pair{ke, erot}); // the first table (15 digits), not the reprint
    } else {
      in_table = false;
    }
  }
  return out;
}

struct DumpAtom {
  Vec3 x, v, w;
};

// The step-100 dump (gzip): id type x y z vx vy vz omegax omegay omegaz fx fy fz.
std::unordered_map<long, DumpAtom> lammps_dump(const std::filesystem::path& gz) {
  gzFile f = gzopen(gz.c_str(), "rb");
  if (!f) throw std::runtime_error(fmt::format("cannot read {}", gz.string()));
  std::unordered_map<long, DumpAtom> out;
  char buf[1024];
  bool atoms = false;
  while (gzgets(f, buf, sizeof buf)) {
    const std::string line(buf);
    if (line.rfind("ITEM: ATOMS", 0) == 0) {
      atoms = true;
      continue;
    }
    if (!atoms) continue;
    std::istringstream row(line);
    long id = 0, type = 0;
    DumpAtom a;
    row >> id >> type >> a.x.x >> a.x.y >> a.x.z >> a.v.x >> a.v.y >> a.v.z >> a.w.x >> a.w.y >>
        a.w.z;
    if (row) out[id] = a;
  }
  gzclose(f);
  return out;
}

CaseResult chute_c1(const Paths& paths) {
  CaseResult res;
  const Scene scene = read_scene_file((paths.scenes / "chute-lammps.toml").string());
  auto sim = build_simulation(scene, false);
  const auto thermo = lammps_thermo(paths.reference_data / "chute_c1.log");
  for (long step : {0L, 50L, 100L}) {
    sim->run(step - sim->step_count());
    const auto e = sim->energies();
    const auto it = thermo.find(step);
    if (it == thermo.end())
      throw std::runtime_error(fmt::format("no thermo line for step {}", step));
    // LAMMPS prints 8 significant digits by default; the reference has 15.
    res.add_relative(fmt::format("step {}: translational KE", step), it->second.first,
                     e.translational, 1e-8);
    res.add_relative(fmt::format("step {}: rotational KE", step), it->second.second, e.rotational,
                     1e-8);
  }
  // Every atom at step 100.
  const auto dump = lammps_dump(paths.reference_data / "chute_c1_step100.dump.gz");
  const auto& s = sim->particles();
  const Box& box = sim->config().box;
  double dx = 0, dv = 0, dw = 0;
  std::size_t matched = 0;
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    const auto it = dump.find(static_cast<long>(s.gid[i]) + 1);
    if (it == dump.end()) continue;
    ++matched;
    dx = std::max(dx, norm(box.minimum_image(s.x[i], it->second.x)));
    dv = std::max(dv, norm(s.v[i] - it->second.v));
    dw = std::max(dw, norm(s.w[i] - it->second.w));
  }
  res.add("atoms matched with the LAMMPS dump", 32000, static_cast<double>(matched), 0);
  res.add("step 100: largest position difference", 0, dx, 1e-10);
  res.add("step 100: largest velocity difference", 0, dv, 1e-8);
  res.add("step 100: largest angular velocity difference", 0, dw, 1e-7);
  return res;
}

// A steady flow down the chute: a periodic lx x ly slice of the LAMMPS chute (its frozen base
// and the grains above it, about 39 grains per d^2), tilted to `degrees`, run for `total` tau,
// its fields coarse-grained along z (docs/coarse-graining.md; a Gaussian of width d / 2, the
// slice averaged over x and y) and averaged over the last fifth, sampled every 0.1 tau.
struct SteadyChute {
  double theta = 0.0; // rad
  analysis::CgGrid grid;
  analysis::CgFields fields;
  Vec3 base_force;                // the mean contact force on the frozen base
  double grain_mass = 0.0;        // the grains' mean total mass
  std::vector<double> window_ke;  // kinetic energy per grain in windows of the second half
  std::vector<double> mass_above; // at each point, per unit area: the integral of rho above
  double total = 0.0;             // tau
};

SteadyChute run_steady_chute(const Paths& paths, const std::string& label, double degrees,
                             double lx, double ly, double total) {
  Scene scene = read_scene_file((paths.scenes / "chute-lammps.toml").string());
  SteadyChute out;
  out.theta = degrees * pi / 180;
  out.total = total;
  const double theta = out.theta;
  scene.sim.gravity = {std::sin(theta), 0.0, -std::cos(theta)};
  scene.sim.box.hi.x = lx;
  scene.sim.box.hi.y = ly;
  // The slice's particles, less the grains that would overlap another particle across the
  // slice's new periodic sides by more than 1 % of a diameter (the LAMMPS packing repeats every
  // 40 d x 20 d: its 20 d x 10 d slice loses none; the frozen base is kept whole).
  std::vector<ParticleSpec> slice;
  for (const auto& p : scene.particles)
    if (p.kind != Kind::grain && p.position.x < lx && p.position.y < ly) slice.push_back(p);
  for (const auto& p : scene.particles) {
    if (p.kind != Kind::grain || !(p.position.x < lx && p.position.y < ly)) continue;
    const bool overlaps = std::any_of(slice.begin(), slice.end(), [&](const ParticleSpec& q) {
      Vec3 d = p.position - q.position;
      d.x -= lx * std::round(d.x / lx);
      d.y -= ly * std::round(d.y / ly);
      const double touch = 0.99 * (p.radius + q.radius);
      return norm2(d) < touch * touch;
    });
    if (!overlaps) slice.push_back(p);
  }
  scene.particles = slice;
  scene.n_lammps_atoms = slice.size();
  scene.sim.on_escape = EscapePolicy::remove;
  auto sim = build_simulation(scene, false);
  const double dt = scene.sim.dt;
  // Kinetic energy of the flowing grains per grain, in windows of total / 20 over the second
  // half of the run: steady flow keeps it within +-2 %
  // (docs/models/validation.md C2, "over 500 tau").
  const auto grain_kinetic = [&sim] {
    const auto& s = sim->particles();
    double ke = 0, n = 0;
    for (std::size_t i = 0; i < s.n_owned(); ++i)
      if (s.is_grain(i)) ke += 0.5 * s.mass[i] * dot(s.v[i], s.v[i]), n += 1;
    return ke / n;
  };
  const auto report = [&](double ke) {
    fmt::print(stderr,
               "{} at {} degrees: t = {:.0f} tau of {:.0f}, kinetic energy per grain {:.4g}\n",
               label, degrees, sim->time(), total, ke);
  };
  const int windows = 10;
  const double window = 0.5 * total / windows;
  std::vector<double>& window_ke = out.window_ke;
  while (sim->time() < 0.5 * total - 0.5 * dt) {
    sim->run(std::llround(window / dt));
    report(grain_kinetic());
  }
  // From half to four fifths: 50 kinetic-energy samples per window.
  const auto steps_per_sample = std::max<std::int64_t>(1, std::llround(window / 50 / dt));
  for (int w = 0; w < windows * 3 / 5; ++w) {
    double sum = 0;
    for (int n = 0; n < 50; ++n) {
      sim->run(steps_per_sample);
      sum += grain_kinetic();
    }
    window_ke.push_back(sum / 50);
    report(window_ke.back());
  }

  // The last fifth.
  analysis::CgSettings cg;
  cg.kind = analysis::CgKind::gaussian;
  cg.width = 0.5;
  cg.cutoff = 3.0 * cg.width;
  cg.grid.lo = {0.0, 0.0, 0.0};
  cg.grid.hi = {lx, ly, 60.0};
  cg.grid.n = {1, 1, 120};
  cg.grid.averaged = {true, true, false};
  cg.grid.periodic = {true, true, false};
  std::vector<double> sums(analysis::cg_sums_per_point * cg.grid.size(), 0.0);
  CoarseGrainInput input;
  double samples = 0, last_fifth_ke = 0;
  std::int64_t samples_in_window = 0;
  while (sim->time() < total) {
    sim->run(std::llround(0.1 / dt) - 1);
    sim->record_contacts(true); // only for the sampled step
    sim->step();
    const auto& s = sim->particles();
    samples += 1;
    last_fifth_ke += grain_kinetic();
    if (++samples_in_window == std::llround(window / 0.1)) {
      window_ke.push_back(last_fifth_ke / static_cast<double>(samples_in_window));
      report(window_ke.back());
      last_fifth_ke = 0, samples_in_window = 0;
    }
    // Force on the base: contact forces on the frozen wall particles (gravity is not applied
    // to them).
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
      if (!s.is_grain(i))
        out.base_force += s.f[i];
      else
        out.grain_mass += s.mass[i];
    }
    input.gather(*sim);
    sim->record_contacts(false);
    const std::vector<double> now = analysis::coarse_grain_sums(input.grains(), input.contacts, cg);
    for (std::size_t k = 0; k < sums.size(); ++k) sums[k] += now[k];
  }
  for (double& sum : sums) sum /= samples;
  out.base_force = out.base_force / samples;
  out.grain_mass /= samples;
  out.grid = cg.grid;
  out.fields = analysis::coarse_grain_fields(sums, cg.grid);
  // The mass above each point per unit area (the trapezoidal rule on the grid, the density zero
  // beyond it).
  const int n_points = cg.grid.n[2];
  const double h = cg.grid.spacing(2);
  out.mass_above.assign(static_cast<std::size_t>(n_points) + 1, 0.0);
  for (int k = n_points - 1; k >= 0; --k) {
    const auto u = static_cast<std::size_t>(k);
    const double next = k + 1 < n_points ? out.fields.density[u + 1] : 0.0;
    out.mass_above[u] = out.mass_above[u + 1] + 0.5 * h * (out.fields.density[u] + next);
  }
  return out;
}

// The bulk of a steady chute flow, 4 d above the floor to 3 d below the surface (the highest
// point where the packing fraction is above 0.3). Steady flow: -d sigma_xz / dz + rho g
// sin(theta) = 0 and -d sigma_zz / dz - rho g cos(theta) = 0 (stresses positive in compression),
// so sigma_zz is the weight above and mu = -sigma_xz / sigma_zz = tan(theta) at every depth. The
// inertial number I = gamma_dot d / sqrt(P / rho_p) (GDR MiDi 2004), P = sigma_zz, rho_p = 6 /
// pi (m = d = 1, g = 1).
struct ChuteBulk {
  double worst_ratio = 0, worst_weight = 0;       // |mu / tan(theta) - 1|, |sigma_zz / weight - 1|
  double phi_min = 1, phi_max = 0, phi_mean = 0;  // packing fraction
  double i_min = 1e300, i_max = 0, i_mean = 0;    // inertial number
  double mu_mean = 0;                             // -sigma_xz / sigma_zz
  double surface = 0;                             // z, d
  std::vector<std::pair<double, double>> profile; // (z, v_x)
};

ChuteBulk chute_bulk(const SteadyChute& c) {
  const analysis::CgFields& f = c.fields;
  const int n_points = c.grid.n[2];
  const double h = c.grid.spacing(2), g = 1.0, rho_p = 6.0 / pi;
  ChuteBulk b;
  for (int k = 0; k < n_points; ++k)
    if (f.volume_fraction[static_cast<std::size_t>(k)] > 0.3) b.surface = c.grid.coordinate(2, k);
  double points = 0;
  for (int k = 1; k + 1 < n_points; ++k) {
    const double z = c.grid.coordinate(2, k);
    if (z < 4.0 || z > b.surface - 3.0) continue;
    const auto u = static_cast<std::size_t>(k);
    const double sxz = f.stress[9 * u + 2], szz = f.stress[9 * u + 8];
    const double mu = -sxz / szz;
    b.worst_ratio = std::max(b.worst_ratio, std::abs(mu / std::tan(c.theta) - 1));
    const double weight = g * std::cos(c.theta) * c.mass_above[u];
    b.worst_weight = std::max(b.worst_weight, std::abs(szz / weight - 1));
    const double phi = f.volume_fraction[u];
    b.phi_min = std::min(b.phi_min, phi), b.phi_max = std::max(b.phi_max, phi);
    const double shear = (f.velocity[3 * (u + 1)] - f.velocity[3 * (u - 1)]) / (2 * h);
    const double inertial = shear * 1.0 / std::sqrt(szz / rho_p);
    b.i_min = std::min(b.i_min, inertial), b.i_max = std::max(b.i_max, inertial);
    b.i_mean += inertial, b.phi_mean += phi, b.mu_mean += mu, points += 1;
    b.profile.emplace_back(z, f.velocity[3 * u]);
  }
  b.i_mean /= points, b.phi_mean /= points, b.mu_mean /= points;
  return b;
}

// R^2 of the Bagnold fit v = A (H^1.5 - (H - z)^1.5) + v0, H = the surface.
double bagnold_r2(const ChuteBulk& b) {
  std::vector<double> x, v;
  for (auto [z, vx] : b.profile) {
    x.push_back(std::pow(b.surface, 1.5) - std::pow(std::max(b.surface - z, 0.0), 1.5));
    v.push_back(vx);
  }
  return analysis::fit_line(x, v).r2;
}

// The spread (max - min) of the windows' kinetic energy over their mean.
double kinetic_spread(const SteadyChute& c) {
  const auto [lo, hi] = std::minmax_element(c.window_ke.begin(), c.window_ke.end());
  const double mean = std::accumulate(c.window_ke.begin(), c.window_ke.end(), 0.0) /
                      static_cast<double>(c.window_ke.size());
  return (*hi - *lo) / mean;
}

double env_tau(const char* name, double fallback) {
  const char* env = std::getenv(name);
  const double total = env ? std::atof(env) : fallback;
  if (!(total > 0))
    throw std::runtime_error(fmt::format("{} must be a positive number of tau", name));
  return total;
}

// C2: steady chute flow (Silbert et al. 2001) on a 20 d x 10 d slice (about 7,800 flowing
// spheres over 228 frozen base spheres) at 24 degrees, run for YUXI_C2_TAU tau (default 1000).
// Exact momentum balance in steady flow: normal force on the base = N m g cos(theta) (0.5 %),
// basal shear / normal force = tan(theta) (1 %), and at every depth of the bulk sigma_xz /
// sigma_zz = tan(theta) and sigma_zz = the weight above (2 %); from the rheology (GDR MiDi
// 2004), a uniform inertial number in the bulk; from the paper's ranges: packing fraction flat
// within 0.02 in the bulk, a Bagnold velocity profile v_x ~ H^1.5 - (H - z)^1.5 (fit R^2 >
// 0.99), and steady flow (kinetic energy within +-2 % over the second half).
// YUXI_C2_PROFILE=file.csv writes the profiles.
CaseResult chute_c2(const Paths& paths) {
  CaseResult res;
  const SteadyChute c =
      run_steady_chute(paths, "C2", 24.0, 20.0, 10.0, env_tau("YUXI_C2_TAU", 1000.0));
  const double theta = c.theta, g = 1.0;
  res.add_relative("normal force on the base / (N m g cos theta)", 1.0,
                   -c.base_force.z / (c.grain_mass * g * std::cos(theta)), 0.005);
  // The grains push the base down (-z) and drag it downhill (+x).
  res.add_relative("basal shear / normal force = tan theta", std::tan(theta),
                   -c.base_force.x / c.base_force.z, 0.01);
  const ChuteBulk b = chute_bulk(c);
  res.add("bulk: largest |sigma_xz / (sigma_zz tan theta) - 1| (coarse-grained)", 0.0,
          b.worst_ratio, 0.02);
  res.add("bulk: largest |sigma_zz / (weight above) - 1| (coarse-grained)", 0.0, b.worst_weight,
          0.02);
  res.add("bulk: packing fraction spread (max - min)", 0.0, b.phi_max - b.phi_min, 0.02);
  res.add("bulk: mean packing fraction (Silbert: 0.55-0.60)", 0.575, b.phi_mean, 0.03);
  // mu(I) = tan(theta) everywhere makes I uniform through the bulk (GDR MiDi 2004).
  res.add("bulk: inertial number spread (max - min) / mean (uniform: mu(I) = tan theta)", 0.0,
          (b.i_max - b.i_min) / b.i_mean, 0.3);
  res.add("Bagnold profile fit R^2 (> 0.99)", 1.0, bagnold_r2(b), 0.01);
  res.add(fmt::format("steady flow: kinetic energy spread over the last {:.0f} tau / mean",
                      0.5 * c.total),
          0.0, kinetic_spread(c), 0.04);
  if (const char* out = std::getenv("YUXI_C2_PROFILE")) {
    const analysis::CgFields& f = c.fields;
    std::ofstream csv(out);
    csv << "z,density,packing_fraction,vx,sigma_xz,sigma_zz,sigma_xx,sigma_yy,kinetic_zz,"
           "weight_above,temperature,coordination\n";
    for (int k = 0; k < c.grid.n[2]; ++k) {
      const auto u = static_cast<std::size_t>(k);
      csv << fmt::format("{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},"
                         "{:.6g}\n",
                         c.grid.coordinate(2, k), f.density[u], f.volume_fraction[u],
                         f.velocity[3 * u], f.stress[9 * u + 2], f.stress[9 * u + 8],
                         f.stress[9 * u], f.stress[9 * u + 4], f.kinetic_stress[9 * u + 8],
                         g * std::cos(theta) * c.mass_above[u], f.temperature[u],
                         f.coordination[u]);
    }
    if (!csv) throw std::runtime_error(fmt::format("cannot write {}", out));
  }
  return res;
}

// C3: the rheology mu(I), phi(I) of the chute (GDR MiDi, Eur. Phys. J. E 14:341, 2004): the
// steady flows of a 10 d x 5 d slice (1,663 grains, about 33 d deep) at 22 to 26 degrees, each
// run for YUXI_C3_TAU tau (default 1000). Each angle gives one point (I, mu, phi), the bulk's
// means. Checks: each flow steady and balanced (below); I rises with the angle (mu(I)
// increasing); phi falls as I rises; the straight lines through the points, mu =
// mu_0 + b I (da Cruz et al., PRE 72:021309, 2005) and phi = phi_0 - a I, meet I = 0 at mu_0
// within tan(17 to 21.5 degrees) (thick layers stop at 19.5-20.5 degrees: Silbert et al. 2001,
// Pouliquen 1999) and at phi_0 within 0.57-0.63 (the packing at which frictional spheres stop
// flowing, da Cruz et al. 2005: 0.60). YUXI_C3_POINTS=file.csv writes the points.
CaseResult chute_c3(const Paths& paths) {
  CaseResult res;
  const double total = env_tau("YUXI_C3_TAU", 1000.0);
  struct Point {
    double degrees, inertial, mu, phi;
  };
  std::vector<Point> points;
  for (const double degrees : {22.0, 23.0, 24.0, 25.0, 26.0}) {
    const SteadyChute c = run_steady_chute(paths, "C3", degrees, 10.0, 5.0, total);
    const ChuteBulk b = chute_bulk(c);
    // Steady: within +-6 % over the second half. The windows' noise in 1,663 grains is about
    // sqrt(7,772 / 1,663) = 2.2 times C2's (its +-2 %); an accelerating or stopping flow changes
    // by far more over 500 tau.
    res.add(fmt::format("{} degrees: kinetic energy spread over the last {:.0f} tau / mean",
                        degrees, 0.5 * total),
            0.0, kinetic_spread(c), 0.12);
    // Balanced: the bulk's mean mu is tan(theta) (1 %); its worst point, noisier than C2's in
    // the smaller slice, within 4 %.
    res.add_relative(fmt::format("{} degrees: bulk mean mu / tan theta", degrees), 1.0,
                     b.mu_mean / std::tan(c.theta), 0.01);
    res.add(fmt::format("{} degrees: bulk, largest |mu / tan theta - 1|", degrees), 0.0,
            b.worst_ratio, 0.04);
    points.push_back({degrees, b.i_mean, b.mu_mean, b.phi_mean});
  }
  bool rising = true, falling = true;
  for (std::size_t k = 1; k < points.size(); ++k) {
    rising = rising && points[k].inertial > points[k - 1].inertial;
    falling = falling && points[k].phi < points[k - 1].phi;
  }
  res.add("I rises with the angle (1 = yes)", 1.0, rising ? 1.0 : 0.0, 0.0);
  res.add("phi falls as I rises (1 = yes)", 1.0, falling ? 1.0 : 0.0, 0.0);
  // Least-squares lines y = y0 + slope I.
  std::vector<double> inertial, mu, phi;
  for (const Point& p : points)
    inertial.push_back(p.inertial), mu.push_back(p.mu), phi.push_back(p.phi);
  const analysis::LineFit mu_line = analysis::fit_line(inertial, mu);
  const analysis::LineFit phi_line = analysis::fit_line(inertial, phi);
  const double mu_0 = mu_line.intercept, mu_slope = mu_line.slope;
  const double phi_0 = phi_line.intercept, phi_slope = phi_line.slope;
  const double lo = std::tan(17.0 * pi / 180), hi = std::tan(21.5 * pi / 180);
  res.add(fmt::format("mu(I) = mu_0 + b I: mu_0 in tan(17-21.5 deg) (b = {:.3g})", mu_slope),
          0.5 * (lo + hi), mu_0, 0.5 * (hi - lo));
  res.add(fmt::format("phi(I) = phi_0 - a I: phi_0 in 0.57-0.63 (a = {:.3g})", -phi_slope), 0.60,
          phi_0, 0.03);
  if (const char* out = std::getenv("YUXI_C3_POINTS")) {
    std::ofstream csv(out);
    csv << "degrees,inertial_number,mu,packing_fraction\n";
    for (const Point& p : points)
      csv << fmt::format("{},{:.6g},{:.6g},{:.6g}\n", p.degrees, p.inertial, p.mu, p.phi);
    if (!csv) throw std::runtime_error(fmt::format("cannot write {}", out));
  }
  return res;
}

} // namespace

std::vector<Case> chute_cases() {
  return {{"C1", "LAMMPS chute benchmark: 100 steps of data.chute against LAMMPS",
           "LAMMPS 29 Sep 2021 (Debian 20220106) on the same file, tests/validation/data", false,
           chute_c1},
          {"C2", "steady chute flow at 24 degrees: momentum balance, packing, Bagnold profile",
           "exact momentum balance; Silbert et al., PRE 64, 051302 (2001)", true, chute_c2},
          {"C3", "chute rheology: mu(I) and phi(I) from steady flows at 22 to 26 degrees",
           "GDR MiDi, EPJE 14:341 (2004); da Cruz et al., PRE 72:021309 (2005); Silbert et al. "
           "2001",
           true, chute_c3}};
}

} // namespace yuxi::validation
