// A simulation's checkpoints: its saved state (Simulation::save_state) in the checkpoint file
// format of io/checkpoint_file.hpp, written and loaded. Here, above both, so that the file
// format knows nothing of the engine.
#pragma once

#include "io/checkpoint_file.hpp"
#include "run/scene_builder.hpp"
#include "sim/simulation.hpp"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace yuxi {

// Collective: writes `file` atomically with the scene and every rank's state. Only a good
// state is kept: throws SimulationError (and writes nothing) where the simulation is unhealthy.
void write_checkpoint(const std::filesystem::path& file, const std::string& scene_text,
                      Simulation& sim);

// Collective: the next checkpoint of a run folder (CheckpointSet); returns the file.
std::filesystem::path write_checkpoint(const CheckpointSet& set, const std::string& scene_text,
                                       Simulation& sim);

// Collective: loads the shares into a simulation built from the checkpoint's scene, in place of
// its state; throws CheckpointError naming the file where the state does not load or fit.
void apply_checkpoint(const CheckpointData& data, Simulation& sim);

// Collective: the checkpoint's state continued under `scene`, built straight from it
// (continue_simulation: as a resume, or with `branch` as a branch); throws CheckpointError
// naming the file where the state does not load or fit, TimeStepError unless `force_dt`.
std::unique_ptr<Simulation> continue_checkpoint(const Scene& scene, const CheckpointData& data,
                                                std::optional<Simulation::BranchCheck> branch,
                                                bool force_dt, BuildReport* report = nullptr);

} // namespace yuxi
