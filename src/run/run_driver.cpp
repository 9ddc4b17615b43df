#include "run/run_driver.hpp"

#include "io/checkpoint_file.hpp"
#include "io/energy_csv.hpp"
#include "io/lammps_dump_writer.hpp"
#include "io/vtk_walls.hpp"
#include "io/vtk_writer.hpp"
#include "run/bed_measurements.hpp"
#include "run/progress.hpp"
#include "run/run_analysis.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <optional>

namespace yuxi {
namespace {

// Steps between two outputs of period `interval` (0: never).
std::int64_t every(double interval, double dt) {
  return interval > 0 ? std::max<std::int64_t>(1, std::llround(interval / dt)) : 0;
}

} // namespace

RunSummary run_to_end(const Scene& scene, Simulation& sim, const RunOptions& options) {
  const auto& dir = options.output_dir;
  const double dt = sim.config().dt;
  const std::int64_t first = sim.step_count();
  const std::int64_t last = std::llround(scene.run.t_end / dt);
  const std::int64_t energy_every = every(scene.output.energy_interval, dt);
  const std::int64_t snapshot_every = every(scene.output.snapshot_interval, dt);

  // A resumed run keeps the rows and frames of the steps up to its checkpoint, except one that
  // the saved run wrote only because it ended there (off the output's interval): extended to a
  // later end, the files are then those of a run straight to it.
  const auto resume_after = [&](std::int64_t interval) -> std::optional<std::int64_t> {
    if (!options.resumed) return std::nullopt;
    const bool off_interval = interval > 0 && first % interval != 0;
    return off_interval && first < last ? first - 1 : first;
  };
  // energies.csv is written by rank 0, from energies reduced over ranks; every rank writes its
  // own particles into the snapshots and checkpoints (no rank gathers the others').
  const bool root = sim.comm().root();
  std::unique_ptr<EnergyCsv> energies;
  std::unique_ptr<VtkSeries> vtk;
  std::unique_ptr<LammpsDumpWriter> dump;
  std::unique_ptr<EnergyCsv> walls;
  if (root)
    energies = std::make_unique<EnergyCsv>(dir / "energies.csv", resume_after(energy_every));
  // walls.csv: per shaped wall, the force and torque the grains put on it and its cumulative
  // work on them (docs/scene-format.md, "walls.csv").
  if (root && !(sim.walls().empty() && sim.planes().empty()))
    walls = std::make_unique<EnergyCsv>(dir / "walls.csv", resume_after(energy_every),
                                        "step,time,wall,fx,fy,fz,torque_x,torque_y,torque_z,"
                                        "work,contacts");
  if (scene.output.vtk && snapshot_every)
    vtk = std::make_unique<VtkSeries>(dir, "particles", resume_after(snapshot_every), sim.comm());
  if (scene.output.lammps_dump && snapshot_every)
    dump = std::make_unique<LammpsDumpWriter>(dir / "particles.lammpstrj", scene.sim.box,
                                              resume_after(snapshot_every), sim.comm());
  // inflow.csv and outflow.csv: each insert's and outlet's cumulative grains and mass.
  std::unique_ptr<EnergyCsv> inflow, outflow;
  if (root && !scene.inserts.empty())
    inflow = std::make_unique<EnergyCsv>(dir / "inflow.csv", resume_after(energy_every),
                                         "step,time,insert,grains,mass,owed");
  if (root && !scene.outlets.empty())
    outflow = std::make_unique<EnergyCsv>(dir / "outflow.csv", resume_after(energy_every),
                                          "step,time,outlet,grains,mass");
  // measurements.csv: the [[measure]] tables' columns.
  std::unique_ptr<BedMeasurements> measures;
  std::unique_ptr<EnergyCsv> measurements;
  if (!scene.measures.empty()) {
    double largest = 0;
    for (std::size_t i = 0; i < sim.particles().n_owned(); ++i)
      if (sim.particles().is_grain(i)) largest = std::max(largest, sim.particles().radius[i]);
    sim.comm().max(&largest, 1);
    for (const InsertSpec& s : scene.inserts) largest = std::max(largest, s.grains.size.largest());
    measures = std::make_unique<BedMeasurements>(scene.measures, sim, largest);
    if (root)
      measurements = std::make_unique<EnergyCsv>(dir / "measurements.csv",
                                                 resume_after(energy_every), measures->header());
  }
  const auto write_measurements = [&] {
    if (!measures) return;
    const std::vector<double> v = measures->values(sim); // collective
    if (!measurements) return;
    std::string row = fmt::format("{},{:.10g}", sim.step_count(), sim.time());
    for (double x : v) row += fmt::format(",{:.10g}", x);
    measurements->write_row(row);
  };
  const auto write_flows = [&] {
    const auto row = [&](EnergyCsv& csv, const Simulation::SourceTally& f, bool owed) {
      csv.write_row(fmt::format("{},{:.10g},{},{},{:.10g}{}", sim.step_count(), sim.time(), f.name,
                                f.grains, f.mass,
                                owed ? fmt::format(",{}", f.owed) : std::string()));
    };
    if (inflow)
      for (const auto& f : sim.inflow()) row(*inflow, f, true);
    if (!scene.outlets.empty()) {
      const auto flows = sim.outflow(); // collective
      for (std::size_t k = 0; outflow && k < flows.size(); ++k) row(*outflow, flows[k], false);
    }
  };
  // Particles in the rate (grains and wall particles), counted again at each row of
  // energies.csv: grains may come and go.
  double n_particles = 0, n_walls = 0;
  const auto write_energies = [&] {
    const EnergyBooks e = sim.energies(); // collective
    n_particles = n_walls + static_cast<double>(e.grains);
    if (energies) energies->write(e);
    write_flows();
    write_measurements();
    const auto row = [&](const std::string& name, const WallLoad& l) {
      walls->write_row(fmt::format("{},{:.10g},{},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},{:.10g},"
                                   "{:.10g},{}",
                                   sim.step_count(), sim.time(), name, l.force.x, l.force.y,
                                   l.force.z, l.torque.x, l.torque.y, l.torque.z, l.work,
                                   l.contacts));
    };
    if (!sim.walls().empty()) {
      const std::vector<WallLoad> loads = sim.wall_loads(); // collective
      for (std::size_t w = 0; walls && w < loads.size(); ++w)
        row(wall_name(sim.walls()[w]), loads[w]);
    }
    if (!sim.planes().empty()) {
      const std::vector<WallLoad> loads = sim.plane_loads(); // collective
      for (std::size_t p = 0; walls && p < loads.size(); ++p) row(sim.planes()[p].name, loads[p]);
    }
  };
  CheckpointSet checkpoints(dir, scene.checkpoint.keep);
  const auto& policy = scene.checkpoint;
  auto last_checkpoint = std::chrono::steady_clock::now();
  // A signal reaches one rank or all; every rank must stop at the same step.
  const auto stop_requested = [&] { return sim.comm().any(options.stop && *options.stop != 0); };
  // A checkpoint may follow any step and leaves the trajectory untouched (see
  // Simulation::checkpoint): a run repeats itself to the bit whenever its checkpoints were
  // written, by step count, by the clock, on a signal or at the end. The signal and the clock
  // are polled every poll_steps steps only: each poll is a collective, and one per step costs
  // more than the step itself on small systems split over ranks.
  const auto seconds_since = [](std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  constexpr std::int64_t poll_steps = 50;
  const auto checkpoint_due = [&](std::int64_t next) {
    if (next == last) return true;
    if (policy.every_steps > 0 && next % policy.every_steps == 0) return true;
    if (next % poll_steps != 0) return false;
    if (stop_requested()) return true;
    const double minutes = seconds_since(last_checkpoint) / 60.0;
    return sim.comm().any(policy.every_minutes > 0 && minutes >= policy.every_minutes);
  };
  RunSummary summary;
  auto snapshot = [&] {
    const auto t0 = std::chrono::steady_clock::now();
    if (vtk) {
      // The shaped walls beside the particles, in the same frame (none: no walls file).
      std::optional<WallSurface> surface;
      if (!sim.walls().empty()) surface = wall_surface(sim); // collective
      vtk->write(sim.particles(), sim.step_count(), sim.time(),
                 surface ? &*surface : nullptr); // collective
    }
    if (dump) dump->write(sim.particles(), sim.step_count());
    summary.snapshot_seconds += seconds_since(t0);
  };

  std::unique_ptr<RunAnalysis> analysis;
  if (scene.analysis)
    analysis = std::make_unique<RunAnalysis>(scene, dir, dt,
                                             options.resumed ? std::optional(first) : std::nullopt);

  Progress progress(first, last, options.show_progress && sim.comm().root());
  n_particles =
      static_cast<double>(sim.comm().sum(static_cast<std::int64_t>(sim.particles().n_owned())));
  n_walls = n_particles - static_cast<double>(sim.energies().grains);
  const auto start = std::chrono::steady_clock::now();
  double particle_steps = 0.0;
  if (!options.resumed) {
    write_energies();
    if (snapshot_every) snapshot();
  }
  try {
    while (sim.step_count() < last) {
      const bool checkpoint_now = checkpoint_due(sim.step_count() + 1);
      if (analysis) analysis->before_step(sim);
      sim.step();
      if (analysis) analysis->after_step(sim);
      particle_steps += n_particles;
      const std::int64_t k = sim.step_count();
      if (k % energy_every == 0 || k == last) write_energies();
      if (snapshot_every && (k % snapshot_every == 0 || k == last)) snapshot();
      if (checkpoint_now) {
        const auto t0 = std::chrono::steady_clock::now();
        checkpoints.write(options.scene_text, sim);
        last_checkpoint = std::chrono::steady_clock::now();
        summary.checkpoint_seconds += seconds_since(t0);
        if (stop_requested()) {
          summary.interrupted = true;
          break;
        }
      }
      progress.update(k, sim.time());
    }
  } catch (const SimulationError& e) {
    progress.finish();
    summary.failed = true;
    summary.failure = e.what();
    if (root) std::ofstream(dir / "failure.txt") << e.what() << "\n";
    write_vtu(dir / "failure.vtu", sim.particles(), sim.comm()); // every rank stopped together
  }
  progress.finish();
  if (analysis && !summary.failed) analysis->finish(sim);
  summary.wall_seconds = seconds_since(start);
  summary.steps = sim.step_count() - first;
  summary.particle_steps_per_second =
      summary.wall_seconds > 0 ? particle_steps / summary.wall_seconds : 0.0;
  summary.final_energies = sim.energies();
  return summary;
}

} // namespace yuxi
