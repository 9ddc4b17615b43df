#include "run/run_opening.hpp"

#include "io/checkpoint_file.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>

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
  // Later checkpoints carry the new settings.
  if (adjust && adjust(r.scene)) r.scene_text = resolved_scene_toml(r.scene);
  r.sim = build_simulation(r.scene, true, &r.report);
  apply_checkpoint(data, *r.sim);
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
  if (!(r.scene.run.t_end > data->time))
    throw SceneError(fmt::format("{}: run.t_end = {} is not after the checkpoint's time t = {}",
                                 r.scene.source, r.scene.run.t_end, data->time));
  r.sim = build_simulation(r.scene, force_dt, &r.report);
  r.scene_text = resolved_scene_toml(r.scene);
  Scene same = r.scene;
  same.run.name = saved.run.name;
  same.run.t_end = saved.run.t_end;
  const bool as_resume = resolved_scene_toml(same) == data->scene_text;
  if (as_resume) {
    apply_checkpoint(*data, *r.sim);
  } else {
    const bool keep = saved.contact_model == r.scene.contact_model;
    if (!keep)
      r.warnings.push_back(fmt::format(
          "the contact model changes from {} to {}: every contact's history (tangential "
          "springs and model state) is dropped, and contacts open afresh under the new law",
          saved.contact_model, r.scene.contact_model));
    try {
      r.sim->branch(data->sections, data->n_sections, {r.report.walls, r.report.grains, keep},
                    data->format_version);
    } catch (const std::invalid_argument& e) {
      throw CheckpointError(fmt::format("{}: {}", data->file.string(), e.what()));
    }
  }
  r.origin = fmt::format("branching from {} at step {}, t = {}{}", data->file.string(), data->step,
                         data->time,
                         as_resume ? " (the scene is the checkpoint's: the run continues as "
                                     "--resume would)"
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
