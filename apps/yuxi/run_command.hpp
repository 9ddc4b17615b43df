// `yuxi run` and `yuxi check`.
#pragma once

#include <optional>
#include <string>

namespace yuxi {

struct RunCommandOptions {
  std::string scene_path; // empty: the built-in default basin
  std::string output_dir; // empty: runs/<scene name>
  std::string resume;     // a run folder to continue from its newest valid checkpoint
  // A checkpoint file, or a run folder's newest valid checkpoint, whose state the scene
  // continues (a branch: the particles, history, walls, time and books from it, the rest from
  // the scene).
  std::string from;
  bool overwrite = false;
  bool force_dt = false;
  std::optional<double> t_end;
  std::string balance_by; // empty: the scene's domain.balance_by
  std::string device;     // empty: the scene's run.device
  bool progress = true;
  bool plots = true; // draw the energy plot, or the basin figures of an [analysis] table
};

// Each returns the process exit code: 0 success, 2 bad input, 3 the simulation had to stop.
int run_command(const RunCommandOptions& options);
int check_command(const RunCommandOptions& options);

} // namespace yuxi
