#include "run/simulation_checkpoint.hpp"

#include "core/archive.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

namespace yuxi {

void write_checkpoint(const std::filesystem::path& file, const std::string& scene_text,
                      Simulation& sim) {
  sim.stop_if_unhealthy(); // only good states are kept
  ArchiveWriter section;
  sim.save_state(section);
  // The largest grain's radius, for a branch that builds no grain: of the grains now, or of
  // those the cells were sized for (a run that itself built none keeps its size for a resume).
  double largest = 0.5 * sim.config().min_contact_reach;
  const ParticleStore& s = sim.particles();
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    if (s.is_grain(i)) largest = std::max(largest, s.radius[i]);
  const CheckpointHead head{scene_text, sim.step_count(), sim.time(), sim.comm().max(largest)};
  write_checkpoint_file(file, sim.comm(), head, section.data());
}

std::filesystem::path write_checkpoint(const CheckpointSet& set, const std::string& scene_text,
                                       Simulation& sim) {
  return set.write(sim.comm(), sim.step_count(), [&](const std::filesystem::path& file) {
    write_checkpoint(file, scene_text, sim);
  });
}

void apply_checkpoint(const CheckpointData& data, Simulation& sim) {
  try {
    sim.load({data.sections, data.n_sections, data.format_version});
  } catch (const std::invalid_argument& e) { // the same on every rank (Simulation::load)
    throw CheckpointError(fmt::format("{}: {}", data.file.string(), e.what()));
  }
}

std::unique_ptr<Simulation> continue_checkpoint(const Scene& scene, const CheckpointData& data,
                                                std::optional<Simulation::BranchCheck> branch,
                                                bool force_dt, BuildReport* report) {
  try {
    return continue_simulation(scene, {data.sections, data.n_sections, data.format_version}, branch,
                               force_dt, report);
  } catch (const std::invalid_argument& e) { // the same on every rank (Simulation's constructor)
    throw CheckpointError(fmt::format("{}: {}", data.file.string(), e.what()));
  }
}

} // namespace yuxi
