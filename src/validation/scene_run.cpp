#include "validation/scene_run.hpp"

#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "run/run_driver.hpp"
#include "run/run_opening.hpp"
#include "run/scene_builder.hpp"
#include "run/simulation_checkpoint.hpp"

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace yuxi::validation {

namespace fs = std::filesystem;

fs::path run_folder(const std::string& name) {
  const char* root = std::getenv("YUXI_VALIDATION_RUNS");
  const fs::path dir =
      (root ? fs::path(root) : fs::temp_directory_path() / "yuxi-validation") / name;
  // A kept folder with checkpoints may continue (run_scene decides).
  if (!(root && fs::exists(dir / "checkpoints"))) fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void run_scene(const Scene& scene, const fs::path& folder, bool progress, const fs::path& from) {
  std::unique_ptr<Simulation> sim;
  RunOptions options;
  options.output_dir = folder;
  options.show_progress = progress;
  options.scene_text = resolved_scene_toml(scene);
  // A run of the same scene saved in the folder continues from its newest checkpoint (a long
  // case goes on across sessions, or further where the scene now ends later); one that reached
  // the end is only read again.
  const auto same_run = [&](const std::string& saved_text) {
    if (saved_text == options.scene_text) return true;
    try {
      Scene saved = read_scene_text(saved_text, scene.source); // (paths resolve as the scene's)
      if (!(saved.run.t_end <= scene.run.t_end)) return false;
      saved.run.t_end = scene.run.t_end;
      return resolved_scene_toml(saved) == options.scene_text;
    } catch (const SceneError&) {
      return false; // a scene this version no longer reads: run afresh
    }
  };
  if (fs::exists(folder / "checkpoints")) {
    const auto saved = CheckpointSet(folder).newest_valid(Comm::world(), nullptr);
    if (saved && same_run(saved->scene_text)) {
      if (saved->step >= std::llround(scene.run.t_end / scene.sim.dt)) return;
      sim = continue_checkpoint(scene, *saved, std::nullopt, false);
      options.resumed = true;
    } else {
      fs::remove_all(folder);
      fs::create_directories(folder);
    }
  }
  if (!sim)
    sim = from.empty() ? build_simulation(scene, false) : open_branch(scene, from, false).sim;
  const RunSummary s = run_to_end(scene, *sim, options);
  if (s.failed)
    throw std::runtime_error(fmt::format("{}: the run failed: {}", scene.source, s.failure));
}

const std::vector<double>& CsvTable::column(const std::string& name) const {
  const auto it = numbers.find(name);
  if (it == numbers.end() || it->second.empty())
    throw std::runtime_error(fmt::format("no column '{}' with values", name));
  return it->second;
}

CsvTable read_csv(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("cannot read {}", path.string()));
  const auto split = [](const std::string& line) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    return cells;
  };
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> names = split(line);
  CsvTable t;
  while (std::getline(in, line)) {
    const auto cells = split(line);
    for (std::size_t c = 0; c < names.size() && c < cells.size(); ++c) {
      char* end = nullptr;
      const double v = std::strtod(cells[c].c_str(), &end);
      const bool number = end != cells[c].c_str() && *end == '\0';
      t.numbers[names[c]].push_back(number ? v : NAN);
      t.text[names[c]].push_back(cells[c]);
    }
    ++t.rows;
  }
  return t;
}

std::map<std::string, std::pair<double, double>> final_flows(const fs::path& path) {
  const CsvTable t = read_csv(path);
  const bool in = t.text.count("insert") > 0;
  const auto& names = t.text.at(in ? "insert" : "outlet");
  std::map<std::string, std::pair<double, double>> out;
  for (std::size_t r = 0; r < t.rows; ++r)
    out[names[r]] = {t.numbers.at("grains")[r], t.numbers.at("mass")[r]};
  return out;
}

} // namespace yuxi::validation
