#include "run_command.hpp"

#include "default_scene.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "plot_script.hpp"
#include "run/progress.hpp"
#include "run/run_driver.hpp"
#include "run/run_opening.hpp"
#include "run/scene_builder.hpp"
#include "run/simulation_checkpoint.hpp"

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace fs = std::filesystem;

namespace yuxi {
namespace {

// Every rank of a job reads the same scene and meets the same bad input: rank 0 says so, once.
void print_error(const std::string& message) {
  if (Comm::world().root()) fmt::print(stderr, "error: {}\n", message);
}

// An error's message with this program's remedy, where it has one.
std::string with_remedy(const std::exception& e) {
  if (dynamic_cast<const TimeStepError*>(&e)) return fmt::format("{} (or pass --force)", e.what());
  if (const auto* f = dynamic_cast<const OutputFolderError*>(&e); f && f->occupied)
    return fmt::format("{}; choose another with -o or pass --overwrite", e.what());
  return e.what();
}

// The command line's overrides of the scene's settings; true where one was given.
bool apply_overrides(const RunCommandOptions& o, Scene& scene) {
  if (!o.balance_by.empty())
    scene.sim.balance_by = o.balance_by == "time" ? BalanceBy::time : BalanceBy::pairs;
  if (!o.device.empty()) scene.run.device = *run_device_named(o.device);
  return !o.balance_by.empty() || !o.device.empty();
}

// A run asked for the device engine that it cannot run says so before its folder is made.
bool device_run_possible(const Scene& scene, const Simulation& sim) {
  const std::optional<DeviceChoice> choice = device_choice(scene.run.device);
  if (!choice) return true;
  try {
    check_device_run(sim, *choice);
    return true;
  } catch (const std::exception& e) {
    print_error(fmt::format("{}\n(run.device = \"{}\"; pass --device cpu to run on the CPU "
                            "engine)",
                            e.what(), run_device_name(scene.run.device)));
    return false;
  }
}

Scene load(const RunCommandOptions& o) {
  Scene scene = o.scene_path.empty() ? read_scene_text(default_scene_text, default_scene_name)
                                     : read_scene_file(o.scene_path);
  if (o.t_end) {
    if (!(*o.t_end > 0)) throw SceneError(fmt::format("--t-end: must be > 0 (got {})", *o.t_end));
    scene.run.t_end = *o.t_end;
  }
  apply_overrides(o, scene);
  if (Comm::world().root())
    for (const auto& w : scene.warnings) fmt::print(stderr, "warning: {}\n", w);
  return scene;
}

void describe(const Scene& scene, const Simulation& sim, const BuildReport& r) {
  for (const auto& w : r.warnings) spdlog::warn("{}", w);
  spdlog::info("scene {} from {}", scene.run.name, scene.source);
  spdlog::info("{} grains, {} wall particles, {} flat walls; domain [{}, {}] x [{}, {}] x [{}, {}]",
               r.grains, r.walls, sim.planes().size(), scene.sim.box.lo.x, scene.sim.box.hi.x,
               scene.sim.box.lo.y, scene.sim.box.hi.y, scene.sim.box.lo.z, scene.sim.box.hi.z);
  const auto& m = scene.materials;
  spdlog::info("time step dt = {:.4g} = t_c / {:.1f} of the stiffest contact ({}-{}: t_c = {:.4g}, "
               "m_eff = {:.4g}{}); {} steps to t = {}",
               scene.sim.dt, 1.0 / r.dt_over_tc, m[r.stiffest.material_a], m[r.stiffest.material_b],
               r.stiffest.contact_time, r.stiffest.m_eff, speed_note(r),
               std::llround(scene.run.t_end / scene.sim.dt) - sim.step_count(), scene.run.t_end);
  const auto e = sim.grid().edge();
  const auto d = sim.grid().dims();
  spdlog::info("linked cells {} x {} x {} of edge {:.4g}, skin {:.4g}; gravity ({}, {}, {}) in "
               "the scene's units",
               d[0] - 2, d[1] - 2, d[2] - 2, e.x, sim.config().skin, scene.sim.gravity.x,
               scene.sim.gravity.y, scene.sim.gravity.z);
}

// Reads, validates and builds the scene; prints the error of bad input and returns false.
bool prepare(const RunCommandOptions& o, Scene& scene, std::unique_ptr<Simulation>& sim) {
  try {
    scene = load(o);
    BuildReport report;
    sim = build_simulation(scene, o.force_dt, &report);
    describe(scene, *sim, report);
    return true;
  } catch (const std::exception& e) { // SceneError, or invalid_argument from the engine
    print_error(with_remedy(e));
    return false;
  }
}

} // namespace

int check_command(const RunCommandOptions& o) {
  Scene scene;
  std::unique_ptr<Simulation> sim;
  if (!prepare(o, scene, sim)) return 2;
  fmt::print("{}: the scene is valid\n", scene.source);
  return 0;
}

volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int sig) {
  stop_signal = sig;
}

// Opens the run of --resume or --from; prints the error of bad input and returns false.
bool open(const RunCommandOptions& o, OpenedRun& run) {
  try {
    if (!o.resume.empty()) {
      run = open_resume(o.resume, [&](Scene& scene) {
        if (o.t_end) scene.run.t_end = *o.t_end;
        return apply_overrides(o, scene) || o.t_end;
      });
    } else {
      run = open_branch(load(o), o.from, o.force_dt);
    }
    if (Comm::world().root())
      for (const auto& w : run.warnings) fmt::print(stderr, "warning: {}\n", w);
    describe(run.scene, *run.sim, run.report);
    spdlog::info("{}", run.origin);
    return true;
  } catch (const std::exception& e) { // SceneError, CheckpointError, invalid_argument
    print_error(with_remedy(e));
    return false;
  }
}

int run_command(const RunCommandOptions& o) {
  OpenedRun run;
  if (o.resume.empty() && o.from.empty()) {
    if (!prepare(o, run.scene, run.sim)) return 2;
    run.scene_text = resolved_scene_toml(run.scene);
  } else if (!open(o, run)) {
    return 2;
  }
  const Scene& scene = run.scene;
  const std::unique_ptr<Simulation>& sim = run.sim;
  const std::string& scene_text = run.scene_text;
  if (!device_run_possible(scene, *sim)) return 2;
  fs::path dir = o.resume;
  if (o.resume.empty()) {
    // (only once the scene is known to be good)
    try {
      dir = create_run_folder(sim->comm(), o.output_dir, scene, o.overwrite, scene_text);
    } catch (const OutputFolderError& e) {
      print_error(with_remedy(e));
      return 2;
    }
  }
  spdlog::info("writing to {}", dir.string());
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);

  RunOptions ro;
  ro.output_dir = dir;
  ro.show_progress = o.progress && Progress::stderr_is_terminal();
  ro.scene_text = scene_text;
  ro.resumed = !o.resume.empty();
  ro.stop = &stop_signal;
  ro.device = device_choice(scene.run.device);
  if (sim->comm().size() > 1)
    spdlog::info("{} MPI ranks: {}; owned particles max/mean {:.3f}", sim->comm().size(),
                 sim->decomposition().describe(), sim->imbalance());
  // The simulation counts list builds from t = 0 (a checkpoint keeps the count); the log gives
  // this run's.
  const std::int64_t builds_before = sim->list_builds();
  const RunSummary s = run_to_end(scene, *sim, ro);
  const auto& t = sim->timers();
  const auto& e = s.final_energies;
  const double imbalance = sim->imbalance(); // collective
  // The load that balancing evens out: each rank's time computing pairs, its own part of the
  // list builds and the integration (the rest is exchanges, waiting for the others, or
  // output), max over the mean.
  const double busy_imbalance = sim->comm().max_over_mean(t.busy());
  // The pairs each rank lists: the work balancing evens out, free of the machine's noise that
  // the compute time carries.
  const double pair_imbalance =
      sim->comm().max_over_mean(static_cast<double>(sim->neighbor_list().n_pairs()));
  const double data_bytes = sim->comm().sum(static_cast<double>(sim->memory_bytes()));
  const double n_particles = sim->comm().sum(static_cast<double>(sim->particles().n_owned()));
  const double listed_pairs =
      sim->comm().sum(static_cast<double>(sim->neighbor_list().n_pairs())); // each pair once
  const double ghosts = sim->comm().sum(static_cast<double>(sim->particles().n_ghost()));
  // Copies of other ranks' particles: each step brings their fields and sends their forces back.
  const double copies = static_cast<double>(sim->halo().n_ghosts_from_other_ranks());
  const double all_copies = sim->comm().sum(copies), most_copies = sim->comm().max(copies);
  const auto inflow = sim->inflow();
  const auto outflow = sim->outflow(); // collective
  // Of each still mesh, a rank holds only the triangles near its sub-domain.
  std::vector<std::string> held_meshes;
  for (const ShapedWall& w : sim->shaped_walls())
    if (const auto* mesh = std::get_if<MeshWall>(&w)) {
      const double held = static_cast<double>(mesh->mesh.n_triangles());
      const double most = sim->comm().max(held), least = -sim->comm().max(-held);
      if (least < static_cast<double>(mesh->whole_mesh().n_triangles()))
        held_meshes.push_back(fmt::format("mesh '{}': each rank holds {:.0f} to {:.0f} of its {} "
                                          "triangles",
                                          mesh->name, least, most,
                                          mesh->whole_mesh().n_triangles()));
    }
  if (!sim->comm().root())
    return s.failed ? 3 : (s.interrupted ? 128 + static_cast<int>(stop_signal) : 0);
  spdlog::info("{} steps in {:.2f} s: {:.0f} steps/s, {:.3g} particle-steps/s", s.steps,
               s.wall_seconds, static_cast<double>(s.steps) / std::max(s.wall_seconds, 1e-9),
               s.particle_steps_per_second);
  // Shares of the run's wall time; what no phase timer covers is output (energies, snapshots,
  // checkpoints, progress) and the analyses.
  const double wall = std::max({s.wall_seconds, t.total(), 1e-9});
  if (s.device.empty())
    spdlog::info(
        "time: pair {:.1f}%  neighbour {:.1f}%  comm {:.1f}%  integrate {:.1f}%  output "
        "and analysis {:.1f}% (snapshots {:.1f}%, checkpoints {:.1f}%{})  ({} list builds){}",
        100 * t.pair / wall, 100 * t.neighbor / wall, 100 * t.comm / wall, 100 * t.integrate / wall,
        100 * (wall - t.total()) / wall, 100 * s.snapshot_seconds / wall,
        100 * s.checkpoint_seconds / wall,
        s.coarse_grain_seconds > 0.0
            ? fmt::format(", coarse-graining {:.1f}%", 100 * s.coarse_grain_seconds / wall)
            : std::string(),
        sim->list_builds() - builds_before,
        sim->comm().size() > 1 ? fmt::format("; rank 0's times; load max/mean {:.3f} in particles, "
                                             "{:.3f} in listed pairs, {:.3f} in compute time",
                                             imbalance, pair_imbalance, busy_imbalance)
                               : std::string());
  if (!s.device.empty()) {
    const auto& p = s.device_phases;
    spdlog::info("device engine on {}: {:.0f} bytes of device memory per particle ({:.0f} at "
                 "most, during list builds and outputs); time: list build {:.1f}%  forces "
                 "{:.1f}%  integrate {:.1f}%  energy books {:.1f}% on the device, handing the "
                 "state to the host {:.1f}%, snapshots {:.1f}%, checkpoints {:.1f}%  ({} list "
                 "builds)",
                 s.device, s.device_bytes_per_particle, s.device_peak_bytes_per_particle,
                 100 * p.list_build / wall, 100 * p.forces / wall, 100 * p.integration / wall,
                 100 * p.books / wall, 100 * s.handover_seconds / wall,
                 100 * s.snapshot_seconds / wall, 100 * s.checkpoint_seconds / wall,
                 sim->list_builds() - builds_before);
  }
  spdlog::info("memory: {:.0f} bytes per particle in particles (with ghosts), cells, neighbour "
               "list and contact states; the list holds {:.0f} pairs ({:.2f} per particle); {:.0f} "
               "ghosts ({:.1f} per 100 particles: {:.0f} periodic images, {:.0f} copies of other "
               "ranks' particles)",
               data_bytes / std::max(n_particles, 1.0), listed_pairs,
               listed_pairs / std::max(n_particles, 1.0), ghosts,
               100 * ghosts / std::max(n_particles, 1.0), ghosts - all_copies, all_copies);
  for (const std::string& line : held_meshes) spdlog::info("{}", line);
  if (all_copies > 0)
    spdlog::info("halo: a step brings the rank with most copies of other ranks' particles {:.0f} "
                 "of them ({:.1f} kB of positions and velocities) and sends {:.1f} kB of their "
                 "forces back",
                 most_copies, most_copies * Halo::forward_bytes_per_ghost / 1e3,
                 most_copies * Halo::reverse_bytes_per_ghost / 1e3);
  spdlog::info("t = {:.4f}: kinetic {:.6g}, elastic {:.6g}, gravitational {:.6g}, dissipated "
               "{:.6g}, wall work {:.6g}; {} contacts, {} grains, {} escaped",
               e.time, e.kinetic(), e.elastic, e.gravitational, e.dissipated, e.wall_work,
               e.contacts, e.grains, e.escaped);
  for (const auto& f : inflow)
    spdlog::info("{}: {} grains inserted ({:.6g} of mass){}", f.name, f.grains, f.mass,
                 f.owed > 0
                     ? fmt::format("; {} due but found no free place in the last batch", f.owed)
                     : std::string());
  for (const auto& f : outflow)
    spdlog::info("{}: {} grains left ({:.6g} of mass)", f.name, f.grains, f.mass);
  if (s.interrupted) {
    fmt::print(stderr,
               "stopped by signal {} at step {}; checkpoint written. Continue with: yuxi "
               "run --resume {}\n",
               static_cast<int>(stop_signal), sim->step_count(), dir.string());
    return 128 + static_cast<int>(stop_signal);
  }
  if (s.failed) {
    fmt::print(stderr, "error: the simulation stopped: {}\n", s.failure);
    fmt::print(stderr, "its last state is in {}\n", (dir / "failure.vtu").string());
    return 3;
  }
  if (o.plots) {
    if (scene.analysis)
      run_plot_script("plot_basin.py", fmt::format("'{}'", dir.string()));
    else
      run_plot_script("plot_energy.py", fmt::format("'{}' '{}'", (dir / "energies.csv").string(),
                                                    (dir / "energies.png").string()));
  }
  fmt::print("{}\n", dir.string());
  return 0;
}

} // namespace yuxi
