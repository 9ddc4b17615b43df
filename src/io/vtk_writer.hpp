// VTK XML output that ParaView opens: one .vtu (unstructured grid of vertex cells, appended raw
// binary data) per snapshot, and a .pvd collection naming them with their times. The .pvd is
// rewritten after each frame, so it is valid whenever the run stops.
#pragma once

#include "core/particle_store.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace yuxi {

// Writes the owned particles of `s` to `path` (.vtu).
void write_vtu(const std::filesystem::path& path, const ParticleStore& s);

class VtkSeries {
public:
  // A new series; or, with `resume_after`, the existing one without the frames after that step
  // (their files are deleted), continued.
  explicit VtkSeries(std::filesystem::path folder, std::string stem = "particles",
                     std::optional<std::int64_t> resume_after = std::nullopt);
  // Writes frame `<stem>_<step>.vtu` and updates `<stem>.pvd`.
  void write(const ParticleStore& s, std::int64_t step, double time);

private:
  std::filesystem::path folder_;
  std::string stem_;
  void write_collection();
  std::vector<std::pair<double, std::string>> frames_;
};

} // namespace yuxi
