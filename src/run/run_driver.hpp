// Runs a built simulation to the scene's end time and writes its outputs into one folder:
//   energies.csv          the energy books every output.energy_interval
//   particles.pvd + .vtu  VTK snapshots every output.snapshot_interval (ParaView)
//   particles.lammpstrj   the same frames as a LAMMPS dump (OVITO)
//   checkpoints/          the run's state every [checkpoint] interval, on SIGINT/SIGTERM and at
//                         the end (checkpoint_file.hpp); a resumed run continues every file
//   failure.txt, failure.vtu   if the run had to stop: the diagnosis and the last state
//   analysis/             the fish-basin analysis of the scene's [analysis] table
//                         (run_analysis.hpp); a run resumed inside the averaging window
//                         averages over the part after the restart
#pragma once

#include "io/scene.hpp"
#include "sim/simulation.hpp"

#include <csignal>
#include <filesystem>
#include <string>

namespace yuxi {

struct RunOptions {
  std::filesystem::path output_dir;
  bool show_progress = false;
  std::string scene_text; // the resolved scene, stored in every checkpoint
  bool resumed = false;   // the simulation was loaded from a checkpoint: continue the files
  const volatile std::sig_atomic_t* stop = nullptr; // set by a signal: checkpoint and return
};

struct RunSummary {
  std::int64_t steps = 0;
  double wall_seconds = 0.0;
  double particle_steps_per_second = 0.0; // (owned particles, grains and walls) x steps / s
  double snapshot_seconds = 0.0;          // wall time writing VTK and LAMMPS dump frames
  double checkpoint_seconds = 0.0;        // wall time writing checkpoints
  EnergyBooks final_energies;
  bool failed = false;
  bool interrupted = false; // stopped by a signal after writing a checkpoint
  std::string failure;      // the diagnosis when failed
};

RunSummary run_to_end(const Scene& scene, Simulation& sim, const RunOptions& options);

} // namespace yuxi
