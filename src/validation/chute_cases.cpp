// The LAMMPS chute benchmark (docs/models/validation.md section 3): C1, 100 steps of data.chute
// against LAMMPS itself (reference output and the command that made it: tests/validation/data); C2,
// steady flow of a slice of it down a 24 degree incline (Silbert et al. 2001).
#include "core/units.hpp"
#include "io/scene_reader.hpp"
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

// C2: steady chute flow (Silbert et al. 2001) on a 20 d x 10 d periodic slice of the LAMMPS
// chute (about 7,800 flowing spheres over 228 frozen base spheres), tilted to 24 degrees, run for
// YUXI_C2_TAU tau (default 1000) and averaged over its last fifth. Exact momentum balance in
// steady flow: normal force on the base = N m g cos(theta) (0.5 %), basal shear / normal force =
// tan(theta) (1 %), and sigma_xz / sigma_zz = tan(theta) at every depth of the bulk (2 %, 3 d
// clear of base and surface); from the paper's ranges: packing fraction flat within 0.01 in the
// bulk, a Bagnold velocity profile v_x ~ H^1.5 - (H - z)^1.5 (fit R^2 > 0.99), and steady flow
// (kinetic energy within +-2 % over the second half). YUXI_C2_PROFILE=file.csv writes the
// layer profiles.
CaseResult chute_c2(const Paths& paths) {
  CaseResult res;
  Scene scene = read_scene_file((paths.scenes / "chute-lammps.toml").string());
  const double theta = 24.0 * pi / 180;
  scene.sim.gravity = {std::sin(theta), 0.0, -std::cos(theta)};
  scene.sim.box.hi.x = 20.0;
  scene.sim.box.hi.y = 10.0;
  std::vector<ParticleSpec> slice;
  for (const auto& p : scene.particles)
    if (p.position.x < 20.0 && p.position.y < 10.0) slice.push_back(p);
  scene.particles = slice;
  scene.n_lammps_atoms = slice.size();
  scene.sim.on_escape = EscapePolicy::remove;
  auto sim = build_simulation(scene, false);
  const char* env = std::getenv("YUXI_C2_TAU");
  const double total = env ? std::atof(env) : 1000.0;
  if (!(total > 0)) throw std::runtime_error("YUXI_C2_TAU must be a positive number of tau");
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
  const auto report = [&sim, total](double ke) {
    fmt::print(stderr, "C2: t = {:.0f} tau of {:.0f}, kinetic energy per grain {:.4g}\n",
               sim->time(), total, ke);
  };
  const int windows = 10;
  const double window = 0.5 * total / windows;
  std::vector<double> window_ke;
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

  // Averages over the last fifth, sampled every 0.1 tau.
  const double area = 20.0 * 10.0, layer = 1.0;
  const int n_layers = 60;
  std::vector<double> sxz(n_layers), szz(n_layers), volume_frac(n_layers), vx(n_layers),
      count(n_layers);
  Vec3 base_force;
  double samples = 0, grains_weight = 0, last_fifth_ke = 0;
  std::int64_t samples_in_window = 0;
  while (sim->time() < total) {
    sim->run(std::llround(0.1 / dt) - 1);
    sim->record_contacts(true); // only for the sampled step
    sim->step();
    sim->record_contacts(false);
    const auto& s = sim->particles();
    const auto& list = sim->neighbor_list();
    samples += 1;
    last_fifth_ke += grain_kinetic();
    if (++samples_in_window == std::llround(window / 0.1)) {
      window_ke.push_back(last_fifth_ke / static_cast<double>(samples_in_window));
      report(window_ke.back());
      last_fifth_ke = 0, samples_in_window = 0;
    }
    // Force on the base: contact forces on the frozen wall particles (gravity is not applied
    // to them).
    double weight = 0;
    for (std::size_t i = 0; i < s.n_owned(); ++i) {
      if (!s.is_grain(i)) {
        base_force += s.f[i];
        continue;
      }
      weight += s.mass[i];
      const int k = static_cast<int>(s.x[i].z / layer);
      if (k < 0 || k >= n_layers) continue;
      const double r = s.radius[i];
      volume_frac[static_cast<std::size_t>(k)] += 4.0 / 3.0 * pi * r * r * r / (area * layer);
      vx[static_cast<std::size_t>(k)] += s.v[i].x;
      count[static_cast<std::size_t>(k)] += 1;
    }
    grains_weight += weight;
    // Method of planes: contact forces acting across the plane z_k, on the material above it.
    for (std::size_t i = 0; i + 1 < list.offsets.size(); ++i)
      for (auto p = list.offsets[i]; p < list.offsets[i + 1]; ++p) {
        const std::size_t j = list.partners[p];
        const Vec3 f = sim->contact_record().pair_force[p]; // on i
        if (f == Vec3{}) continue;
        const double hi = std::max(s.x[i].z, s.x[j].z), lo = std::min(s.x[i].z, s.x[j].z);
        const Vec3 on_upper = s.x[i].z >= s.x[j].z ? f : -f;
        for (int k = static_cast<int>(std::ceil(lo / layer)); k <= static_cast<int>(hi / layer);
             ++k)
          if (k >= 0 && k < n_layers) {
            // traction on the material below from the material above: -on_upper
            sxz[static_cast<std::size_t>(k)] += -on_upper.x / area;
            szz[static_cast<std::size_t>(k)] += -on_upper.z / area;
          }
      }
  }
  const double g = 1.0, m_over_n = grains_weight / samples;
  base_force = base_force / samples;
  res.add_relative("normal force on the base / (N m g cos theta)", 1.0,
                   -base_force.z / (m_over_n * g * std::cos(theta)), 0.005);
  // The grains push the base down (-z) and drag it downhill (+x).
  res.add_relative("basal shear / normal force = tan theta", std::tan(theta),
                   -base_force.x / base_force.z, 0.01);
  // Bulk: layers with grains, 3 d clear of the base and the surface.
  int top = 0;
  for (int k = 0; k < n_layers; ++k)
    if (count[static_cast<std::size_t>(k)] / samples > 1.0) top = k;
  double phi_min = 1, phi_max = 0, worst_ratio = 0;
  std::vector<std::pair<double, double>> profile;
  for (int k = 4; k <= top - 3; ++k) {
    const auto u = static_cast<std::size_t>(k);
    // Traction on the material below from the material above: compressive (-z) and dragged
    // downhill (+x), so sigma_xz / sigma_zz = -tan(theta) in the tension-positive convention.
    // Kinetic (streaming) stress is left out: in this dense flow it is three orders of
    // magnitude below the contact stress in the bulk (Silbert et al. 2001).
    const double ratio = -sxz[u] / szz[u];
    worst_ratio = std::max(worst_ratio, std::abs(ratio / std::tan(theta) - 1));
    phi_min = std::min(phi_min, volume_frac[u] / samples);
    phi_max = std::max(phi_max, volume_frac[u] / samples);
    profile.emplace_back((k + 0.5) * layer, vx[u] / count[u]);
  }
  res.add("bulk: largest |sigma_xz / (sigma_zz tan theta) - 1|", 0.0, worst_ratio, 0.02);
  res.add("bulk: packing fraction spread (max - min)", 0.0, phi_max - phi_min, 0.02);
  res.add("bulk: mean packing fraction (Silbert: 0.55-0.60)", 0.575, 0.5 * (phi_max + phi_min),
          0.03);
  // Bagnold fit v = A (H^1.5 - (H - z)^1.5) + v0, H = top of the flow.
  const double h = top + 1.0;
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (auto [z, v] : profile) {
    const double x = std::pow(h, 1.5) - std::pow(std::max(h - z, 0.0), 1.5);
    sx += x, sy += v, sxx += x * x, sxy += x * v, n += 1;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx), icpt = (sy - slope * sx) / n;
  double ss_res = 0, ss_tot = 0;
  for (auto [z, v] : profile) {
    const double x = std::pow(h, 1.5) - std::pow(std::max(h - z, 0.0), 1.5);
    ss_res += (v - slope * x - icpt) * (v - slope * x - icpt);
    ss_tot += (v - sy / n) * (v - sy / n);
  }
  res.add("Bagnold profile fit R^2 (> 0.99)", 1.0, 1 - ss_res / ss_tot, 0.01);
  const auto [ke_min, ke_max] = std::minmax_element(window_ke.begin(), window_ke.end());
  const double ke_mean = std::accumulate(window_ke.begin(), window_ke.end(), 0.0) /
                         static_cast<double>(window_ke.size());
  res.add(fmt::format("steady flow: kinetic energy spread over the last {:.0f} tau / mean",
                      0.5 * total),
          0.0, (*ke_max - *ke_min) / ke_mean, 0.04);
  if (const char* out = std::getenv("YUXI_C2_PROFILE")) {
    std::ofstream csv(out);
    // Layer k holds the grains with k d <= z < (k + 1) d; the stresses act across its floor.
    csv << "z_floor,z_centre,packing_fraction,vx,grains,sigma_xz_floor,sigma_zz_floor\n";
    for (int k = 0; k <= top; ++k) {
      const auto u = static_cast<std::size_t>(k);
      csv << fmt::format("{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", k * layer, (k + 0.5) * layer,
                         volume_frac[u] / samples, count[u] > 0 ? vx[u] / count[u] : 0.0,
                         count[u] / samples, sxz[u] / samples, szz[u] / samples);
    }
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
           "exact momentum balance; Silbert et al., PRE 64, 051302 (2001)", true, chute_c2}};
}

} // namespace yuxi::validation
