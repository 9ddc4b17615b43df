// Advances a simulation on the device engine (run/device_run.hpp): the engine holds the state
// between the steps at which the host needs it (outputs, checkpoints, hooks), and hands it back
// to the Simulation there (Simulation::take_engine_state), so that every output and checkpoint
// is written as on the CPU engine. A checkpoint so written resumes on either engine, and on the
// device engine bit for bit.
#pragma once

#include "run/device_run.hpp"
#include "sim/engine_state.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace yuxi {

class Simulation;

class DeviceStepper {
public:
  // Starts the engine from `sim`'s state. Throws as make_device_engine does.
  DeviceStepper(Simulation& sim, DeviceChoice choice);
  ~DeviceStepper();
  DeviceStepper(const DeviceStepper&) = delete;
  DeviceStepper& operator=(const DeviceStepper&) = delete;

  // Advances `steps` steps on the device. Where the simulation was edited since the engine took
  // its state (Simulation::edits: the Python API's changes between steps), the engine starts
  // again from it first, and throws as the constructor does. A run that cannot go on (a grain
  // out of the box with on_escape = "stop") throws SimulationError, and the simulation keeps the
  // state last handed over.
  void advance(std::int64_t steps);
  // Gives the engine's state to the simulation (nothing where it has it already).
  void hand_over();
  // The energy books now, from the device alone (no hand-over): a row of energies.csv. Summed
  // in the engine's fixed order, so within round-off of the simulation's books of the same
  // state, and the same bits on the GPU and the host build.
  EnergyBooks books() const;
  // Each owned particle's elastic energy at the last force evaluation, half of each of its
  // contacts', in the simulation's order (an analysis's per-grain energies;
  // run/particle_elastic_energy.hpp on the CPU engine). After hand_over().
  std::vector<double> particle_elastic_energy() const;
  // The engine's step count and time.
  std::int64_t step() const;
  double time() const;
  // The device's name, and the bytes it holds now per particle (`peak`: the most it held at
  // once, DeviceMemory::peak).
  std::string device_name() const;
  double device_bytes_per_particle(bool peak = false) const;
  // Each phase's wall time on the device, over every engine this stepper started [s].
  device::DevicePhaseSeconds phase_seconds() const;
  // Wall time spent stepping on the device, and handing the state to the host [s].
  double device_seconds() const { return device_seconds_; }
  double handover_seconds() const { return handover_seconds_; }

private:
  void start();
  EngineState engine_state() const;

  Simulation& sim_;
  DeviceChoice choice_;
  std::uint64_t edits_seen_ = 0;
  bool handed_over_ = true;            // the simulation holds the engine's state
  device::DevicePhaseSeconds earlier_; // of the engines before this one
  std::unique_ptr<device::DeviceEngine> engine_;
  EnergyBooks start_; // the simulation's cumulative books when the engine started
  std::int64_t start_step_ = 0, start_builds_ = 0;
  std::vector<double> start_plane_work_; // each plane's cumulative work when the engine started
  double device_seconds_ = 0, handover_seconds_ = 0;
};

} // namespace yuxi
