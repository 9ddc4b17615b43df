#include "run/run_driver.hpp"

#include "io/energy_csv.hpp"
#include "io/lammps_dump_writer.hpp"
#include "io/vtk_writer.hpp"
#include "run/bed_measurements.hpp"
#include "run/coarse_grain_output.hpp"
#include "run/device_stepper.hpp"
#include "run/progress.hpp"
#include "run/run_analysis.hpp"
#include "run/simulation_checkpoint.hpp"
#include "run/wall_snapshot.hpp"

#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <optional>
#include <stdexcept>

namespace yuxi {
namespace {

// Steps between two outputs of period `interval` (0: never).
std::int64_t every(double interval, double dt) {
  return interval > 0 ? std::max<std::int64_t>(1, std::llround(interval / dt)) : 0;
}

} // namespace

struct RunDriver::Impl {
  const Scene& scene;
  Simulation& sim;
  RunOptions options;
  double dt;
  std::int64_t first, last, energy_every, snapshot_every;
  bool root;
  std::unique_ptr<EnergyCsv> energies, walls, inflow, outflow, measurements;
  std::unique_ptr<VtkSeries> vtk;
  std::unique_ptr<LammpsDumpWriter> dump;
  std::unique_ptr<BedMeasurements> measures;
  std::unique_ptr<CoarseGrainOutput> coarse; // [[coarse_grain]]
  std::unique_ptr<RunAnalysis> analysis;
  std::optional<CheckpointSet> checkpoints;
  std::unique_ptr<DeviceStepper> stepper; // the device engine, where the run is on it
  std::chrono::steady_clock::time_point last_checkpoint, start;
  // Particles in the rate (grains and wall particles), counted again at each row of
  // energies.csv: grains may come and go.
  double n_particles = 0, n_walls = 0, particle_steps = 0;
  RunSummary summary;

  Impl(const Scene& s, Simulation& sm, RunOptions o);
  std::optional<std::int64_t> resume_after(std::int64_t interval) const;
  void write_measurements();
  void write_flows();
  // A row of energies.csv (and walls.csv, inflow.csv, outflow.csv, measurements.csv): of the
  // books `given` (the device engine's), or the simulation's.
  void write_energies(const EnergyBooks* given = nullptr);
  void snapshot();
  bool stop_requested() const;
  bool checkpoint_due(std::int64_t next) const;
  std::int64_t next_host_step(std::int64_t until, const StepHook& hook) const;
  std::filesystem::path write_checkpoint();
};

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The signal and the clock are polled every poll_steps steps only: each poll is a collective,
// and one per step costs more than the step itself on small systems split over ranks.
constexpr std::int64_t poll_steps = 50;

} // namespace

RunDriver::Impl::Impl(const Scene& s, Simulation& sm, RunOptions o)
    : scene(s), sim(sm), options(std::move(o)), dt(sim.config().dt), first(sim.step_count()),
      last(std::llround(scene.run.t_end / dt)),
      energy_every(every(scene.output.energy_interval, dt)),
      snapshot_every(every(scene.output.snapshot_interval, dt)), root(sim.comm().root()) {
  if (options.device) {
    check_device_run(sim, *options.device);
    stepper = std::make_unique<DeviceStepper>(sim, *options.device);
  }
  const auto& dir = options.output_dir;
  // energies.csv is written by rank 0, from energies reduced over ranks; every rank writes its
  // own particles into the snapshots and checkpoints (no rank gathers the others').
  if (root)
    energies = std::make_unique<EnergyCsv>(dir / "energies.csv", resume_after(energy_every));
  // walls.csv: per shaped wall, the force and torque the grains put on it and its cumulative
  // work on them (docs/scene-format.md, "walls.csv").
  if (root && !(sim.shaped_walls().empty() && sim.planes().empty()))
    walls = std::make_unique<EnergyCsv>(dir / "walls.csv", resume_after(energy_every),
                                        "step,time,wall,fx,fy,fz,torque_x,torque_y,torque_z,"
                                        "work,contacts");
  if (scene.output.vtk && snapshot_every)
    vtk = std::make_unique<VtkSeries>(dir, "particles", resume_after(snapshot_every), sim.comm());
  // The dump's mol column where the run has clumps: the scene's shapes, or a state continued
  // with clumps under a scene of none (collective: every rank writes the same header).
  const bool has_clumps =
      !scene.shapes.empty() || sim.comm().max(sim.clumps().empty() ? 0.0 : 1.0) > 0.0;
  if (scene.output.lammps_dump && snapshot_every)
    dump = std::make_unique<LammpsDumpWriter>(dir / "particles.lammpstrj", scene.sim.box,
                                              resume_after(snapshot_every), sim.comm(), has_clumps);
  // inflow.csv and outflow.csv: each insert's and outlet's cumulative grains and mass.
  if (root && !scene.inserts.empty())
    inflow = std::make_unique<EnergyCsv>(dir / "inflow.csv", resume_after(energy_every),
                                         "step,time,insert,grains,mass,owed");
  if (root && !scene.outlets.empty())
    outflow = std::make_unique<EnergyCsv>(dir / "outflow.csv", resume_after(energy_every),
                                          "step,time,outlet,grains,mass");
  // measurements.csv: the [[measure]] tables' columns.
  if (!scene.measures.empty()) {
    double largest = 0;
    for (std::size_t i = 0; i < sim.particles().n_owned(); ++i)
      if (sim.particles().is_grain(i)) largest = std::max(largest, sim.particles().radius[i]);
    sim.comm().max(&largest, 1);
    for (const InsertSpec& i : scene.inserts) largest = std::max(largest, i.grains.size.largest());
    measures = std::make_unique<BedMeasurements>(scene.measures, sim, largest);
    if (root)
      measurements = std::make_unique<EnergyCsv>(dir / "measurements.csv",
                                                 resume_after(energy_every), measures->header());
  }
  // coarse_grain/<name>/: the [[coarse_grain]] tables' fields. The device engine records no
  // contacts: there, a table writes the kinetic fields alone (its fields need no contact, or
  // contacts = false).
  if (!scene.coarse_grains.empty()) {
    if (stepper)
      for (const CoarseGrainSpec& c : scene.coarse_grains)
        if (contact_parts(c).any())
          throw std::invalid_argument(fmt::format(
              "[[coarse_grain]] '{}': its contact fields need the contacts, which the device "
              "engine does not record; name kinetic fields only (density, velocity, "
              "kinetic_stress, temperature, ...) or set contacts = false there, or run on the "
              "CPU engine (--device cpu)",
              c.name));
    coarse = std::make_unique<CoarseGrainOutput>(scene.coarse_grains, sim, dir, dt);
  }
  checkpoints.emplace(dir, scene.checkpoint.keep);
  last_checkpoint = std::chrono::steady_clock::now();
  if (scene.analysis)
    analysis = std::make_unique<RunAnalysis>(scene, dir, dt,
                                             options.resumed ? std::optional(first) : std::nullopt);
  // On the device engine the per-grain elastic energies come from its contacts, at the samples.
  if (analysis && stepper)
    analysis->set_elastic_energy(
        [this](Simulation&) { return stepper->particle_elastic_energy(); });
  n_particles =
      static_cast<double>(sim.comm().sum(static_cast<std::int64_t>(sim.particles().n_owned())));
  n_walls = n_particles - static_cast<double>(sim.energies().grains);
  start = std::chrono::steady_clock::now();
  if (!options.resumed) {
    write_energies();
    if (snapshot_every) snapshot();
  }
}

// A resumed run keeps the rows and frames of the steps up to its checkpoint, except one that
// the saved run wrote only because it ended there (off the output's interval): extended to a
// later end, the files are then those of a run straight to it.
std::optional<std::int64_t> RunDriver::Impl::resume_after(std::int64_t interval) const {
  if (!options.resumed) return std::nullopt;
  const bool off_interval = interval > 0 && first % interval != 0;
  return off_interval && first < last ? first - 1 : first;
}

void RunDriver::Impl::write_measurements() {
  if (!measures) return;
  const std::vector<double> v = measures->values(sim); // collective
  if (!measurements) return;
  std::string row = fmt::format("{},{:.10g}", sim.step_count(), sim.time());
  for (double x : v) row += fmt::format(",{:.10g}", x);
  measurements->write_row(row);
}

void RunDriver::Impl::write_flows() {
  const auto row = [&](EnergyCsv& csv, const Simulation::SourceTally& f, bool owed) {
    csv.write_row(fmt::format("{},{:.10g},{},{},{:.10g}{}", sim.step_count(), sim.time(), f.name,
                              f.grains, f.mass, owed ? fmt::format(",{}", f.owed) : std::string()));
  };
  if (inflow)
    for (const auto& f : sim.inflow()) row(*inflow, f, true);
  if (!scene.outlets.empty()) {
    const auto flows = sim.outflow(); // collective
    for (std::size_t k = 0; outflow && k < flows.size(); ++k) row(*outflow, flows[k], false);
  }
}

void RunDriver::Impl::write_energies(const EnergyBooks* given) {
  const EnergyBooks e = given ? *given : sim.energies(); // collective
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
  if (!sim.shaped_walls().empty()) {
    const std::vector<WallLoad> loads = sim.shaped_wall_loads(); // collective
    for (std::size_t w = 0; walls && w < loads.size(); ++w)
      row(wall_name(sim.shaped_walls()[w]), loads[w]);
  }
  if (!sim.planes().empty()) {
    const std::vector<WallLoad> loads = sim.plane_loads(); // collective
    for (std::size_t p = 0; walls && p < loads.size(); ++p) row(sim.planes()[p].name, loads[p]);
  }
}

void RunDriver::Impl::snapshot() {
  const auto t0 = std::chrono::steady_clock::now();
  if (vtk) {
    // The shaped walls beside the particles, in the same frame (none: no walls file).
    std::optional<WallSurface> surface;
    if (!sim.shaped_walls().empty()) surface = wall_surface(sim); // collective
    vtk->write(sim.particles(), sim.step_count(), sim.time(), surface ? &*surface : nullptr,
               sim.clumps()); // collective
  }
  if (dump) dump->write(sim.particles(), sim.step_count());
  summary.snapshot_seconds += seconds_since(t0);
}

// A signal reaches one rank or all; every rank must stop at the same step.
bool RunDriver::Impl::stop_requested() const {
  bool here = options.stop && *options.stop != 0;
  if (options.stop_requested) here = options.stop_requested() || here;
  return sim.comm().any(here);
}

// A checkpoint may follow any step and leaves the trajectory untouched (see
// Simulation::save_state): a run repeats itself to the bit whenever its checkpoints were
// written, by step count, by the clock, on a signal or at the end.
bool RunDriver::Impl::checkpoint_due(std::int64_t next) const {
  const auto& policy = scene.checkpoint;
  if (next == last) return true;
  if (policy.every_steps > 0 && next % policy.every_steps == 0) return true;
  if (next % poll_steps != 0) return false;
  if (stop_requested()) return true;
  const double minutes = seconds_since(last_checkpoint) / 60.0;
  return sim.comm().any(policy.every_minutes > 0 && minutes >= policy.every_minutes);
}

// The next step after which the host needs the state (an output, a checkpoint, a hook, a poll
// of the signal and the clock), at most `until`: the device engine runs to it in one go.
std::int64_t RunDriver::Impl::next_host_step(std::int64_t until, const StepHook& hook) const {
  const std::int64_t k = stepper ? stepper->step() : sim.step_count();
  std::int64_t next = std::min(until, last);
  const auto due = [&](std::int64_t period) {
    if (period > 0) next = std::min(next, (k / period + 1) * period);
  };
  due(energy_every);
  due(snapshot_every);
  due(poll_steps);
  due(scene.checkpoint.every_steps);
  if (hook.call) due(hook.every);
  if (analysis) next = std::min(next, analysis->next_step_after(k));
  if (coarse) next = std::min(next, coarse->next_sample_after(k));
  return next;
}

std::filesystem::path RunDriver::Impl::write_checkpoint() {
  const auto t0 = std::chrono::steady_clock::now();
  const std::filesystem::path file = yuxi::write_checkpoint(*checkpoints, options.scene_text, sim);
  last_checkpoint = std::chrono::steady_clock::now();
  summary.checkpoint_seconds += seconds_since(t0);
  return file;
}

RunDriver::RunDriver(const Scene& scene, Simulation& sim, RunOptions options)
    : impl_(std::make_unique<Impl>(scene, sim, std::move(options))) {}

RunDriver::~RunDriver() = default;

std::int64_t RunDriver::end_step() const {
  return impl_->last;
}

void RunDriver::set_end_time(double t_end) {
  impl_->last = std::llround(t_end / impl_->dt);
}

void RunDriver::set_show_progress(bool on) {
  impl_->options.show_progress = on;
}

void RunDriver::scene_changed(const std::string& scene_text) {
  Impl& d = *impl_;
  d.options.scene_text = scene_text;
  if (!d.root) return;
  std::ofstream(d.options.output_dir / "scene.resolved.toml") << scene_text;
  if (!d.inflow && !d.scene.inserts.empty())
    d.inflow = std::make_unique<EnergyCsv>(d.options.output_dir / "inflow.csv", std::nullopt,
                                           "step,time,insert,grains,mass,owed");
}

std::filesystem::path RunDriver::write_checkpoint() {
  return impl_->write_checkpoint();
}

bool RunDriver::advance(std::int64_t until, const StepHook& hook) {
  Impl& d = *impl_;
  Simulation& sim = d.sim;
  if (d.summary.failed) return false;
  d.summary.stopped = d.summary.interrupted = false;
  until = std::min(until, d.last);
  Progress progress(sim.step_count(), until, d.options.show_progress && sim.comm().root(),
                    d.options.progress_sink);
  try {
    // The step reached: the simulation's, or the device engine's, which hands its state to the
    // simulation only where the host needs it (a poll of the signal and the clock does not).
    const auto reached = [&] { return d.stepper ? d.stepper->step() : sim.step_count(); };
    bool recording = false; // contacts recorded for this step's coarse-graining sample
    while (reached() < until) {
      // The CPU engine steps once; the device engine to the next step the host needs.
      const std::int64_t now = reached();
      const std::int64_t next = d.stepper ? d.next_host_step(until, hook) : now + 1;
      const bool checkpoint_now = d.checkpoint_due(next);
      if (d.stepper) {
        d.particle_steps += d.n_particles * static_cast<double>(next - now);
        d.stepper->advance(next - now);
      } else {
        // The contacts of a coarse-graining sample are recorded on its step only.
        recording =
            d.coarse && d.coarse->needs_contacts_at(now + 1) && !sim.contact_record().enabled;
        if (recording) sim.record_contacts(true);
        if (d.analysis) d.analysis->before_step(sim);
        sim.step();
        if (d.analysis) d.analysis->after_step(sim);
        d.particle_steps += d.n_particles;
      }
      const std::int64_t k = reached();
      const bool coarse_due = d.coarse && d.coarse->next_sample_after(k - 1) == k;
      const bool energy_row = k % d.energy_every == 0 || k == d.last;
      const bool frame = d.snapshot_every && (k % d.snapshot_every == 0 || k == d.last);
      const bool hook_due = hook.every > 0 && k % hook.every == 0 && hook.call;
      const bool analysis_due = d.stepper && d.analysis && d.analysis->next_step_after(k - 1) == k;
      const bool host_needs_state = frame || hook_due || checkpoint_now || analysis_due ||
                                    coarse_due || k == until || d.measures || d.walls;
      if (d.stepper && energy_row && !host_needs_state) {
        // A row of the device's own books; a gain that nothing put in brings the state back,
        // whose check stops the run with the diagnosis.
        const EnergyBooks books = d.stepper->books();
        if (sim.books_unstable(books)) d.stepper->hand_over();
        d.write_energies(&books);
      } else {
        if (d.stepper && (energy_row || host_needs_state)) d.stepper->hand_over();
        if (energy_row) d.write_energies();
      }
      if (analysis_due) d.analysis->after_step(sim);
      if (coarse_due) {
        const auto t0 = std::chrono::steady_clock::now();
        d.coarse->sample(sim); // collective
        d.summary.coarse_grain_seconds += seconds_since(t0);
      }
      if (recording) sim.record_contacts(false), recording = false;
      if (frame) d.snapshot();
      // Every rank calls the hook at the same step, and any one that says stop stops them all
      // there (a decision from this rank's particles alone would leave the others waiting).
      bool go_on = true;
      if (hook_due) go_on = !sim.comm().any(!hook.call());
      if (checkpoint_now) {
        d.write_checkpoint();
        if (d.stop_requested()) {
          d.summary.interrupted = true;
          break;
        }
      }
      progress.update(k, d.stepper ? d.stepper->time() : sim.time());
      if (!go_on) {
        d.summary.stopped = true;
        break;
      }
    }
  } catch (const SimulationError& e) {
    progress.finish();
    d.summary.failed = true;
    d.summary.failure = e.what();
    if (d.root) std::ofstream(d.options.output_dir / "failure.txt") << e.what() << "\n";
    // (every rank stopped together)
    write_vtu(d.options.output_dir / "failure.vtu", sim.particles(), sim.comm());
  }
  progress.finish();
  return !(d.summary.failed || d.summary.interrupted);
}

RunSummary RunDriver::finish() {
  Impl& d = *impl_;
  if (d.analysis && !d.summary.failed) d.analysis->finish(d.sim);
  d.analysis.reset();
  d.summary.wall_seconds = seconds_since(d.start);
  d.summary.steps = d.sim.step_count() - d.first;
  d.summary.particle_steps_per_second =
      d.summary.wall_seconds > 0 ? d.particle_steps / d.summary.wall_seconds : 0.0;
  d.summary.final_energies = d.sim.energies();
  if (d.stepper) {
    d.summary.device = d.stepper->device_name();
    d.summary.device_bytes_per_particle = d.stepper->device_bytes_per_particle();
    d.summary.device_peak_bytes_per_particle = d.stepper->device_bytes_per_particle(true);
    d.summary.device_seconds = d.stepper->device_seconds();
    d.summary.handover_seconds = d.stepper->handover_seconds();
    d.summary.device_phases = d.stepper->phase_seconds();
  }
  return d.summary;
}

std::optional<DeviceChoice> device_choice(RunDevice device) {
  switch (device) {
  case RunDevice::gpu:
    return DeviceChoice::cuda;
  case RunDevice::host:
    return DeviceChoice::host;
  case RunDevice::cpu:
    break;
  }
  return std::nullopt;
}

void check_device_run(const Simulation& sim, DeviceChoice choice) {
  const std::vector<std::string> no = device_engine_refusals(sim);
  if (!no.empty()) {
    std::string what = "the device engine does not run this scene's";
    for (const std::string& line : no) what += "\n  - " + line;
    throw std::invalid_argument(what);
  }
  check_device_choice(choice);
}

RunSummary run_to_end(const Scene& scene, Simulation& sim, const RunOptions& options) {
  RunDriver driver(scene, sim, options);
  driver.advance(driver.end_step());
  return driver.finish();
}

} // namespace yuxi
