// A simulation's checkpoints: its saved state (Simulation::save_state) in the checkpoint file
// format of io/checkpoint_file.hpp, written and loaded. Here, above both, so that the file
// format knows nothing of the engine.
#pragma once

#include "io/checkpoint_file.hpp"
#include "sim/simulation.hpp"

#include <filesystem>
#include <string>

namespace yuxi {

// Collective: writes `file` atomically with the scene and every rank's state. Only a good
// state is kept: throws SimulationError (and writes nothing) where the simulation is unhealthy.
void write_checkpoint(const std::filesystem::path& file, const std::string& scene_text,
                      Simulation& sim);

// Collective: the next checkpoint of a run folder (CheckpointSet); returns the file.
std::filesystem::path write_checkpoint(const CheckpointSet& set, const std::string& scene_text,
                                       Simulation& sim);

// Collective: loads the shares into a simulation built from the checkpoint's scene; throws
// CheckpointError naming the file where the state does not load or fit.
void apply_checkpoint(const CheckpointData& data, Simulation& sim);

} // namespace yuxi
