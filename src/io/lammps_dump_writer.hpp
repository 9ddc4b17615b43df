// LAMMPS-style text dump ("dump custom" layout) that OVITO opens as a particle trajectory:
// all frames appended to one file. Columns: id type radius mass x y z vx vy vz omegax omegay
// omegaz fx fy fz, with type = material index + 1.
#pragma once

#include "core/box.hpp"
#include "core/particle_store.hpp"

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>

namespace yuxi {

class LammpsDumpWriter {
public:
  // A new file; or, with `resume_after`, the existing one cut before the first frame of a later
  // step, continued.
  LammpsDumpWriter(const std::filesystem::path& path, const Box& box,
                   std::optional<std::int64_t> resume_after = std::nullopt);
  ~LammpsDumpWriter();
  LammpsDumpWriter(const LammpsDumpWriter&) = delete;
  LammpsDumpWriter& operator=(const LammpsDumpWriter&) = delete;

  void write(const ParticleStore& s, std::int64_t step);

private:
  std::FILE* file_;
  Box box_;
};

} // namespace yuxi
