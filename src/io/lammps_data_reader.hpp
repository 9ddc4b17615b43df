// Reads a LAMMPS data file of atom_style sphere, so that yuxi can start from the same state as
// a LAMMPS run (LAMMPS documentation, read_data):
//   header:   "N atoms", "N atom types", "xlo xhi", "ylo yhi", "zlo zhi" (others ignored)
//   Atoms:    id type diameter density x y z [ix iy iz]   (mass = density * 4/3 pi (d/2)^3)
//   Velocities: id vx vy vz wx wy wz
// Sections other than Atoms and Velocities (Masses, coefficients) are skipped. Any malformed
// line is an error naming the file and line.
#pragma once

#include "core/box.hpp"

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace yuxi {

class DataFileError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct LammpsAtom {
  std::int64_t id = 0;
  int type = 0;
  double diameter = 0, density = 0;
  Vec3 x, v, w;
};

struct LammpsData {
  Vec3 lo, hi;
  int n_types = 0;
  std::vector<LammpsAtom> atoms; // sorted by id
};

LammpsData read_lammps_data(const std::filesystem::path& path);
LammpsData parse_lammps_data(std::string_view text, const std::string& source);

} // namespace yuxi
