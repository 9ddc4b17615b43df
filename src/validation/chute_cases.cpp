// The LAMMPS chute benchmark (validation.md section 3): C1, 100 steps of data.chute against
// LAMMPS itself (reference output and the command that made it: tests/validation/data).
#include "io/scene_builder.hpp"
#include "io/scene_reader.hpp"
#include "validation/validation_case.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
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

} // namespace

std::vector<Case> chute_cases() {
  return {{"C1", "LAMMPS chute benchmark: 100 steps of data.chute against LAMMPS",
           "LAMMPS 29 Sep 2021 (Debian 20220106) on the same file, tests/validation/data", false,
           chute_c1}};
}

} // namespace yuxi::validation
