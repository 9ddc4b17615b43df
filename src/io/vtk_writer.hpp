// VTK XML output that ParaView opens: one .vtu (unstructured grid of vertex cells, appended raw
// binary data) per snapshot, with the scene's shaped walls, if it has any, beside it in a .vtp
// (vtk_walls.hpp), the clumps, if there are any, in a second .vtu (a vertex at each centre of
// mass, with its orientation, principal axes and velocities), and a .pvd collection naming them
// with their times (the particles as part 0, the walls as part 1, the clumps as part 2). The .pvd
// is rewritten after each frame, so it is valid whenever the run stops. On several MPI ranks every
// rank writes its own particles into the one .vtu (no rank gathers the others'); rank 0 writes the
// walls.
#pragma once

#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "io/vtk_walls.hpp"
#include "sim/clump_bodies.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace yuxi {

// Writes the owned particles of `s` on every rank of `comm` to `path` (.vtu; collective): rank 0's
// particles first, then rank 1's, ..., each rank's in ascending id.
void write_vtu(const std::filesystem::path& path, const ParticleStore& s,
               const Comm& comm = Comm::self());
// Writes every rank's clumps (their bodies, sim/clump_bodies.hpp) to `path` (.vtu; collective):
// rank 0's first, each rank's in ascending id.
void write_clumps_vtu(const std::filesystem::path& path, std::span<const ClumpBody> clumps,
                      const Comm& comm = Comm::self());

class VtkSeries {
public:
  // A new series; or, with `resume_after`, the existing one without the frames after that step
  // (their files are deleted), continued. Every rank of `comm` makes one (collective).
  explicit VtkSeries(std::filesystem::path folder, std::string stem = "particles",
                     std::optional<std::int64_t> resume_after = std::nullopt,
                     const Comm& comm = Comm::self());
  // Writes frame `<stem>_<step>.vtu` from every rank's owned particles; given `walls`,
  // `walls_<step>.vtp` from rank 0's (the same on every rank); where any rank has clumps,
  // `clumps_<step>.vtu` from every rank's; and updates `<stem>.pvd` (collective).
  void write(const ParticleStore& s, std::int64_t step, double time,
             const WallSurface* walls = nullptr, std::span<const ClumpBody> clumps = {});

private:
  // One file of the collection: a part (0 the particles, 1 the walls, 2 the clumps) at a time.
  struct DataSet {
    double time;
    int part;
    std::string file;
  };
  Comm comm_;
  std::filesystem::path folder_;
  std::string stem_;
  void write_collection();
  std::vector<DataSet> frames_;
  bool clumps_shown_ = false; // a frame had clumps (on rank 0 after a resume: from the .pvd)
};

} // namespace yuxi
