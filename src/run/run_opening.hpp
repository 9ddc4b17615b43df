// The three ways a run opens, shared by `yuxi run` and the Python API: a scene from its start,
// a run folder resumed from its newest valid checkpoint, and a branch (a checkpoint's state
// continued under another scene: docs/ARCHITECTURE.md, "Branching from a checkpoint").
#pragma once

#include "io/scene.hpp"
#include "run/scene_builder.hpp"
#include "sim/simulation.hpp"

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace yuxi {

struct OpenedRun {
  Scene scene;
  std::unique_ptr<Simulation> sim;
  std::string scene_text; // the resolved scene, for the run folder and every checkpoint
  BuildReport report;
  // What the log should say: checkpoints refused, a contact history dropped, where the state
  // came from. (Rank 0 prints them.)
  std::vector<std::string> warnings;
  std::string origin;
};

// A scene from t = 0. Throws SceneError (bad scene, time step too large unless `force_dt`).
OpenedRun open_scene(Scene scene, bool force_dt);

// The newest valid checkpoint of `run_folder`, under the scene it saved; `adjust`, if given,
// may change that scene (a later end time) and returns true where it did. Throws
// CheckpointError where no checkpoint is valid, SceneError where the saved scene is refused.
OpenedRun open_resume(const std::filesystem::path& run_folder,
                      const std::function<bool(Scene&)>& adjust = {});

// The state of `from` (a checkpoint file, or a run folder's newest valid one) continued under
// `scene`. A scene whose dynamics are the checkpoint's (it differs only in its name and end
// time, outputs, checkpoints, analysis, measures, inserts and outlets) continues as a resume
// does, bit for bit, its inserts and outlets taking the saved ones' state by name. Throws
// SceneError (other materials, an end before the checkpoint's time) or CheckpointError (no valid
// checkpoint, particles that are not the scene's).
OpenedRun open_branch(Scene scene, const std::filesystem::path& from, bool force_dt);

// Collective: the run folder `output` (runs/<scene name> when empty), created empty by rank 0
// with the resolved scene in it (scene.resolved.toml). A folder that holds files is refused
// unless `overwrite` (then emptied). Throws OutputFolderError on every rank with rank 0's
// reason.
std::filesystem::path create_run_folder(const Comm& comm, const std::filesystem::path& output,
                                        const Scene& scene, bool overwrite,
                                        const std::string& scene_text);

} // namespace yuxi
