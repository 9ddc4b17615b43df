#include "run/run_opening.hpp"

#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "run/simulation_checkpoint.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <regex>

namespace fs = std::filesystem;

namespace yuxi {
namespace {

// The newest valid checkpoint of a run folder; those refused are noted.
CheckpointData newest_checkpoint(const fs::path& run_folder, const std::string& purpose,
                                 std::vector<std::string>& warnings) {
  std::vector<std::string> refused;
  const Comm comm = Comm::world(); // (every rank reads its share of the checkpoint)
  auto data = CheckpointSet(run_folder).newest_valid(comm, &refused);
  for (const auto& r : refused)
    warnings.push_back(fmt::format("checkpoint refused: {}; trying an older one", r));
  if (!data)
    throw CheckpointError(fmt::format("{}: no valid checkpoint to {}",
                                      (run_folder / "checkpoints").string(), purpose));
  return std::move(*data);
}

// The scene as far as it sets the dynamics: without its name and end, its outputs, checkpoints,
// analysis and measures, and its inserts and outlets (whose grains are the checkpoint's, and
// whose state a checkpoint keeps by name).
std::string dynamics_of(Scene s) {
  s.run.name.clear();
  s.run.t_end = 1.0;
  s.output = {};
  s.checkpoint = {};
  s.analysis.reset();
  s.measures.clear();
  s.inserts.clear();
  s.outlets.clear();
  return resolved_scene_toml(s);
}

// A branch matches its inserts with the checkpoint's by name. An unnamed insert is named by its
// place ("insert[2]"): where the scene's insert of such a name pours from another region or
// other grains than the checkpoint's, it is not the same insert, and the match would be wrong.
void check_unnamed_inserts(const Scene& scene, const Scene& saved) {
  static const std::regex by_place(R"(insert\[\d+\])");
  for (const InsertSpec& s : scene.inserts) {
    if (!std::regex_match(s.name, by_place)) continue;
    for (const InsertSpec& o : saved.inserts) {
      if (o.name != s.name) continue;
      const auto& a = s.grains;
      const auto& b = o.grains;
      const bool same = s.region.describe() == o.region.describe() &&
                        a.size.describe() == b.size.describe() && a.material == b.material &&
                        a.density == b.density && a.seed == b.seed;
      if (!same)
        throw SceneError(fmt::format(
            "{}: {} pours from another region or other grains than the checkpoint's {}: a "
            "branch matches inserts by name, and an unnamed insert is named by its place. Give "
            "the inserts names (name = \"...\"), so that a new insert is not taken for an old "
            "one",
            scene.source, s.name, o.name));
    }
  }
}

} // namespace

OpenedRun open_scene(Scene scene, bool force_dt) {
  OpenedRun r;
  r.scene = std::move(scene);
  r.sim = build_simulation(r.scene, force_dt, &r.report);
  r.scene_text = resolved_scene_toml(r.scene);
  return r;
}

OpenedRun open_resume(const fs::path& run_folder, const std::function<bool(Scene&)>& adjust) {
  OpenedRun r;
  const CheckpointData data = newest_checkpoint(run_folder, "resume from", r.warnings);
  r.scene_text = data.scene_text;
  r.scene = read_scene_text(r.scene_text, (run_folder / "scene.resolved.toml").string());
  size_for_saved_grains(r.scene, data.largest_grain_radius); // (a run branched without grains)
  // Later checkpoints carry the new settings.
  if (adjust && adjust(r.scene)) r.scene_text = resolved_scene_toml(r.scene);
  if (r.scene.run.t_end < data.time - 0.5 * r.scene.sim.dt)
    throw SceneError(fmt::format("run.t_end = {} is before the time of {}, t = {}: a run goes "
                                 "forwards only (give a later end)",
                                 r.scene.run.t_end, data.file.string(), data.time));
  r.sim = continue_checkpoint(r.scene, data, std::nullopt, true, &r.report);
  r.origin =
      fmt::format("resuming from {} at step {}, t = {}", data.file.string(), data.step, data.time);
  return r;
}

OpenedRun open_branch(Scene scene, const fs::path& from, bool force_dt) {
  OpenedRun r;
  r.scene = std::move(scene);
  const Comm comm = Comm::world();
  std::optional<CheckpointData> data;
  if (fs::is_directory(from))
    data = newest_checkpoint(from, "start from", r.warnings);
  else
    data = read_checkpoint(from.string(), comm);
  // (named as the scene of the run that wrote it, which resolves relative paths as resume)
  const Scene saved = read_scene_text(
      data->scene_text, (data->file.parent_path().parent_path() / "scene.resolved.toml").string());
  if (saved.materials != r.scene.materials)
    throw SceneError(fmt::format(
        "{}: materials: [{}] are not the checkpoint's [{}] ({}): a branch keeps the materials "
        "of the run it starts from, in their order",
        r.scene.source, fmt::join(r.scene.materials, ", "), fmt::join(saved.materials, ", "),
        data->file.string()));
  check_unnamed_inserts(r.scene, saved);
  if (!(r.scene.run.t_end > data->time))
    throw SceneError(fmt::format("{}: run.t_end = {} is not after the checkpoint's time t = {}",
                                 r.scene.source, r.scene.run.t_end, data->time));
  // A scene that builds no grain takes them all from the checkpoint: cells and skin for them,
  // and the time-step check once they are loaded.
  const bool own_grains = r.scene.largest_grain_radius > 0.0;
  if (!own_grains) {
    if (!(data->largest_grain_radius > 0.0))
      throw SceneError(fmt::format(
          "{}: the scene has no grains, and {} (format {}) does not say how large its grains "
          "are: add a [[particle]], [[fill]] or [[insert]] with their size",
          r.scene.source, data->file.string(), data->format_version));
    size_for_saved_grains(r.scene, data->largest_grain_radius);
  }
  r.scene_text = resolved_scene_toml(r.scene);
  // A scene whose dynamics are the checkpoint's (it may pour, drain, measure and write
  // otherwise) continues as a resume does, bit for bit, with its own sources.
  const bool as_resume = dynamics_of(r.scene) == dynamics_of(saved) &&
                         r.scene.sim.min_contact_reach == saved.sim.min_contact_reach;
  std::optional<Simulation::BranchCheck> branch;
  if (!as_resume) {
    branch = Simulation::BranchCheck{scene_wall_particles(r.scene),
                                     saved.contact_model == r.scene.contact_model};
    if (!branch->keep_history)
      r.warnings.push_back(fmt::format(
          "the contact model changes from {} to {}: every contact's history (tangential "
          "springs and model state) is dropped, and contacts open afresh under the new law",
          saved.contact_model, r.scene.contact_model));
  }
  r.sim = continue_checkpoint(r.scene, *data, branch, force_dt, &r.report);
  r.origin = fmt::format("branching from {} at step {}, t = {}{}", data->file.string(), data->step,
                         data->time,
                         as_resume ? " (the scene's dynamics are the checkpoint's: the run "
                                     "continues as --resume would, with this scene's sources "
                                     "and outputs)"
                                   : "");
  return r;
}

fs::path create_run_folder(const Comm& comm, const fs::path& output, const Scene& scene,
                           bool overwrite, const std::string& scene_text) {
  const fs::path dir = output.empty() ? fs::path("runs") / scene.run.name : output;
  std::string error;
  bool occupied = false;
  if (comm.root()) {
    try {
      if (fs::exists(dir) && !fs::is_empty(dir)) {
        occupied = !overwrite;
        if (occupied)
          throw std::runtime_error(
              fmt::format("output folder {} already holds a run", dir.string()));
        fs::remove_all(dir);
      }
      fs::create_directories(dir);
      std::ofstream(dir / "scene.resolved.toml") << scene_text;
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  error = comm.first_error(error);
  if (!error.empty()) throw OutputFolderError(error, comm.any(occupied));
  return dir;
}

} // namespace yuxi
