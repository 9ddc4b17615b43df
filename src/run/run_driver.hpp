// Runs a built simulation and writes its outputs into one folder:
//   energies.csv          the energy books every output.energy_interval
//   particles.pvd + .vtu  VTK snapshots every output.snapshot_interval (ParaView)
//   particles.lammpstrj   the same frames as a LAMMPS dump (OVITO)
//   checkpoints/          the run's state every [checkpoint] interval, on SIGINT/SIGTERM and at
//                         the end (checkpoint_file.hpp); a resumed run continues every file
//   failure.txt, failure.vtu   if the run had to stop: the diagnosis and the last state
//   analysis/             the fish-basin analysis of the scene's [analysis] table
//                         (run_analysis.hpp); a run resumed inside the averaging window
//                         averages over the part after the restart
// `yuxi run` goes to the end in one call (run_to_end); the Python API advances a RunDriver in
// pieces, with a callback between steps, and the files are the same as in one go.
#pragma once

#include "io/scene.hpp"
#include "run/device_run.hpp"
#include "sim/simulation.hpp"

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace yuxi {

struct RunOptions {
  std::filesystem::path output_dir;
  bool show_progress = false;
  std::string scene_text; // the resolved scene, stored in every checkpoint
  bool resumed = false;   // the simulation was loaded from a checkpoint: continue the files
  const volatile std::sig_atomic_t* stop = nullptr; // set by a signal: checkpoint and return
  // Asked, with the signal, whether to stop (the Python API's Ctrl-C); every rank must be asked.
  std::function<bool()> stop_requested;
  // Where progress lines go (standard error when empty); `line` starts with '\r'.
  std::function<void(const std::string& line)> progress_sink;
  // The device engine steps the run (docs/gpu.md); empty: the CPU engine. The state comes back
  // to the simulation at each output, checkpoint and hook step.
  std::optional<DeviceChoice> device;
};

// The engine that run.device names: empty for the CPU engine.
std::optional<DeviceChoice> device_choice(RunDevice device);

// Throws std::invalid_argument listing device_engine_refusals, or std::runtime_error where the
// choice is cuda and this build has no CUDA: a run asked for the device is checked before its
// folder is made.
void check_device_run(const Simulation& sim, DeviceChoice choice);

struct RunSummary {
  std::int64_t steps = 0;
  double wall_seconds = 0.0;
  double particle_steps_per_second = 0.0; // (owned particles, grains and walls) x steps / s
  double snapshot_seconds = 0.0;          // wall time writing VTK and LAMMPS dump frames
  double checkpoint_seconds = 0.0;        // wall time writing checkpoints
  double coarse_grain_seconds = 0.0;      // wall time sampling and writing [[coarse_grain]] tables
  // On the device engine: its name, its memory per particle, and the wall time stepping there
  // and handing the state back to the host.
  std::string device;
  double device_bytes_per_particle = 0.0, device_seconds = 0.0, handover_seconds = 0.0;
  double device_peak_bytes_per_particle = 0.0; // the most held at once (DeviceMemory::peak)
  device::DevicePhaseSeconds device_phases;    // within device_seconds
  EnergyBooks final_energies;
  bool failed = false;
  bool interrupted = false; // stopped by a signal after writing a checkpoint
  bool stopped = false;     // stopped by a step hook (no checkpoint forced)
  std::string failure;      // the diagnosis when failed
};

// Called every `every` steps after a step, on every rank; returns false to stop the run there.
// Collective: where any rank's call returns false, every rank stops at that step.
struct StepHook {
  std::int64_t every = 0; // 0: never
  std::function<bool()> call;
};

class RunDriver {
public:
  // Opens the output files (continued where `options.resumed`) and, for a fresh run, writes the
  // rows and frame of step 0. Collective.
  RunDriver(const Scene& scene, Simulation& sim, RunOptions options);
  ~RunDriver();
  RunDriver(const RunDriver&) = delete;
  RunDriver& operator=(const RunDriver&) = delete;

  // Steps until step `until` (clamped to the end step), a signal, a hook's stop or a failure.
  // Returns false if the run may not go on (failed or interrupted). Collective.
  bool advance(std::int64_t until, const StepHook& hook = {});
  // The step at which the run ends (the scene's t_end); a later end extends the run as
  // `--resume --t-end` does.
  std::int64_t end_step() const;
  void set_end_time(double t_end);
  void set_show_progress(bool on);
  // The scene changed under way (an insert added): checkpoints and the run folder's
  // scene.resolved.toml take `scene_text`, and inflow.csv is opened where it was not.
  void scene_changed(const std::string& scene_text);
  // Writes a checkpoint into the run folder now; returns the file. Collective.
  std::filesystem::path write_checkpoint();
  // Ends the run's analysis and returns what it did (also after a failure). Collective.
  RunSummary finish();

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The whole run in one go: RunDriver, advanced to its end, finished.
RunSummary run_to_end(const Scene& scene, Simulation& sim, const RunOptions& options);

} // namespace yuxi
