#include "collide_command.hpp"

#include "contact/contact_model.hpp"
#include "io/scene_reader.hpp"
#include "plot_script.hpp"
#include "thermo/two_grain.hpp"
#include "validation/binary_collision.hpp"
#include "validation/collision_study.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/os.h>
#include <optional>
#include <spdlog/spdlog.h>
#include <stdexcept>

namespace yuxi {
namespace fs = std::filesystem;
namespace {

using validation::exact_setup;
using validation::StudyLaw;

// Restitution against impact speed, every model, head-on: Fig. 4.
void sweep_speeds(const CollideOptions& o, const std::vector<StudyLaw>& runs, const fs::path& dir) {
  auto csv = fmt::output_file((dir / "restitution.csv").string());
  csv.print("model,source,v0,impact_speed,e_n,contact_time,peak_force,max_overlap,heat_fraction,"
            "energy_drift,final_drift\n");
  const std::vector<double> v0s = validation::study_speeds(o.v0_min, o.v0_max, o.per_decade);
  for (const auto& s : runs) {
    for (const auto& r :
         validation::restitution_sweep({s}, v0s, o.mass, o.radius, o.steps_per_contact))
      csv.print("{},{},{:.6g},{:.6g},{:.8f},{:.6g},{:.6g},{:.6g},{:.6g},{:.3g},{:.3g}\n", r.model,
                r.source, r.v0, r.impact_speed, r.e_n, r.contact_time, r.peak_force, r.max_overlap,
                r.heat_fraction, r.energy_drift, r.final_drift);
    spdlog::info("{}: {} impact speeds", s.name, v0s.size());
  }
}

// Oblique impacts at v0 = 1e-3 (spec T13): with rotation, with rotation locked, and the exact
// 2-D solution (no rotation) for the thermodynamic model.
void sweep_obliquity(const CollideOptions& o, const std::vector<StudyLaw>& runs,
                     const fs::path& dir) {
  auto csv = fmt::output_file((dir / "oblique.csv").string());
  csv.print("model,source,impact_parameter,e_n,e_t,v_rel_after_x,v_rel_after_y,spin_0_z,spin_1_z,"
            "heat_fraction,energy_drift\n");
  const double v0 = 1e-3;
  for (const auto& s : runs) {
    const auto exact = exact_setup(s.law, o.mass, o.radius);
    for (double b : o.obliquities) {
      for (bool spins : {true, false}) {
        validation::BinaryCollision c;
        c.law = s.law;
        c.radius = o.radius;
        c.mass = o.mass;
        c.v0 = v0;
        c.impact_parameter = b;
        c.steps_per_contact = o.steps_per_contact;
        c.spins = spins;
        const auto r = validation::collide_binary(c);
        const Vec3 dv = r.v_after[0] - r.v_after[1];
        csv.print("{},{},{},{:.8f},{:.6f},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.3g}\n", s.name,
                  spins ? "engine" : "engine-locked", b, r.e_n, r.e_t, dv.x, dv.y, r.w_after[0].z,
                  r.w_after[1].z, r.heat, r.max_drift);
      }
      if (exact) {
        auto e = *exact;
        e.v0 = v0;
        e.impact_parameter = b;
        const auto x = thermo::collide(e);
        csv.print("{},exact-2d,{},{:.8f},{:.6f},,,0,0,{:.6g},{:.3g}\n", s.name, b, x.restitution,
                  x.tangential_restitution, (x.final_heat + x.final_w_relax) / x.initial_energy,
                  x.max_energy_error);
      }
    }
  }
}

// The head-on time series of the thermodynamic model at v0 = 1e-3 (spec T14, Fig. 3).
void write_series(const CollideOptions& o, const std::vector<StudyLaw>& runs, const fs::path& dir) {
  for (const auto& s : runs) {
    const auto x = validation::head_on_series(s.law, o.mass, o.radius);
    if (!x) continue;
    auto csv = fmt::output_file((dir / "collision_series.csv").string());
    csv.print("t,x1,delta,fn,un,w_el,kinetic,mechanical,w_relax,heat,total\n");
    const double e0 = x->initial_energy;
    for (const auto& p : x->series)
      csv.print("{:.8g},{:.10g},{:.8g},{:.8g},{:.8g},{:.8g},{:.8g},{:.8g},{:.8g},{:.8g},{:.12g}\n",
                p.t, p.x1, p.delta, p.fn, p.un, p.w_el / e0, p.kinetic / e0, p.mechanical / e0,
                p.w_relax / e0, p.heat / e0, p.total / e0);
    spdlog::info("time series of the head-on collision (v0 = 1e-3): e = {:.6f}, E_total kept to "
                 "{:.2g}",
                 x->restitution, x->max_energy_error);
    return;
  }
}

} // namespace

std::vector<std::string> built_in_models() {
  return validation::built_in_models();
}

int collide_command(const CollideOptions& o) {
  try {
    const fs::path dir = o.output_dir;
    if (fs::exists(dir) && !fs::is_empty(dir)) {
      if (!o.overwrite)
        throw std::invalid_argument(
            fmt::format("output folder {} is not empty; choose another with -o or pass --overwrite",
                        dir.string()));
      fs::remove_all(dir);
    }
    fs::create_directories(dir);
    const auto runs = validation::study_laws(o.scene_path, o.models);
    sweep_speeds(o, runs, dir);
    sweep_obliquity(o, runs, dir);
    write_series(o, runs, dir);
    spdlog::info("results in {}", dir.string());
    if (o.plots) run_plot_script("plot_collide.py", fmt::format("'{}'", dir.string()));
    return 0;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
}

} // namespace yuxi
