// LAMMPS-style text dump ("dump custom" layout) that OVITO opens as a particle trajectory:
// all frames appended to one file. Columns: id type radius mass x y z vx vy vz omegax omegay
// omegaz fx fy fz, with type = material index + 1.
#pragma once

#include "core/box.hpp"
#include "core/particle_store.hpp"

#include <cstdio>
#include <filesystem>

namespace yuxi {

class LammpsDumpWriter {
public:
  LammpsDumpWriter(const std::filesystem::path& path, const Box& box);
  ~LammpsDumpWriter();
  LammpsDumpWriter(const LammpsDumpWriter&) = delete;
  LammpsDumpWriter& operator=(const LammpsDumpWriter&) = delete;

  void write(const ParticleStore& s, std::int64_t step);

private:
  std::FILE* file_;
  Box box_;
};

} // namespace yuxi
