// LAMMPS-style text dump ("dump custom" layout) that OVITO opens as a particle trajectory:
// all frames appended to one file. Columns: id type radius mass x y z vx vy vz omegax omegay
// omegaz fx fy fz, with type = material index + 1, and, for a run with clumps, mol: the clump
// a particle is a member of (its id; -1: none), which OVITO reads as the molecule. On several MPI
// ranks every rank writes its own particles' lines into the frame (rank 0's first, each rank's in
// ascending id), as LAMMPS does; OVITO identifies particles by the id column.
#pragma once

#include "core/box.hpp"
#include "core/particle_store.hpp"
#include "domain/comm.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>

namespace yuxi {

class LammpsDumpWriter {
public:
  // A new file; or, with `resume_after`, the existing one cut before the first frame of a later
  // step, continued. Every rank of `comm` makes one (collective). `clumps`: the mol column, a
  // member's clump id + 1 (0 for a grain of no clump: LAMMPS's and OVITO's "no molecule").
  LammpsDumpWriter(const std::filesystem::path& path, const Box& box,
                   std::optional<std::int64_t> resume_after = std::nullopt,
                   const Comm& comm = Comm::self(), bool clumps = false);

  // Appends a frame of every rank's owned particles (collective).
  void write(const ParticleStore& s, std::int64_t step);

private:
  void start_file(std::optional<std::int64_t> resume_after); // rank 0: empty, or cut to resume
  std::filesystem::path path_;
  Box box_;
  Comm comm_;
  bool clumps_;
};

} // namespace yuxi
