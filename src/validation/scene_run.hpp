// The bulk benchmarks run a shipped scene as `yuxi run` would, into a folder that keeps the
// run's files for the plot scripts, and read back the tables the run wrote.
#pragma once

#include "io/scene.hpp"
#include "validation/validation_case.hpp"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace yuxi::validation {

// The folder a case's run writes into: $YUXI_VALIDATION_RUNS/<name> when that is set (kept when
// it holds checkpoints, for run_scene to continue), else <temp>/yuxi-validation/<name>, emptied.
std::filesystem::path run_folder(const std::string& name);

// Runs `scene` to its end into `folder` (progress on stderr when
// `progress`): from the newest checkpoint there when it holds a run of the same scene (and not
// at all when that run has ended), else from the start, or, where `from` names another run's
// folder, from that run's newest checkpoint (a branch, `yuxi run SCENE --from FOLDER`).
// Throws std::runtime_error naming the scene if it fails.
void run_scene(const Scene& scene, const std::filesystem::path& folder, bool progress,
               const std::filesystem::path& from = {});

// A CSV table: its columns by name, each a column of numbers (a cell that is not a number, such
// as a name, reads as NaN; the names of a text column are in `text`).
struct CsvTable {
  std::map<std::string, std::vector<double>> numbers;
  std::map<std::string, std::vector<std::string>> text;
  std::size_t rows = 0;
  const std::vector<double>& column(const std::string& name) const;
  double last(const std::string& name) const { return column(name).back(); }
};
CsvTable read_csv(const std::filesystem::path& path);

// The last row of each named source in inflow.csv or outflow.csv: name -> (grains, mass).
std::map<std::string, std::pair<double, double>> final_flows(const std::filesystem::path& path);

} // namespace yuxi::validation
