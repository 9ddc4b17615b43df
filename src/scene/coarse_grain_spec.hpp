// What a [[coarse_grain]] table asks a run to write: continuum fields of the grains on a grid
// every `interval` (docs/coarse-graining.md, "In a run"; analysis/coarse_grain.hpp computes
// them). Lengths and times in the scene's units.
#pragma once

#include "core/vec3.hpp"

#include <array>
#include <string>
#include <vector>

namespace yuxi {

struct CoarseGrainSpec {
  std::string name;                  // its folder: coarse_grain/<name>/
  std::string function = "gaussian"; // gaussian, lucy or bins
  double width = 0.0;                // w (gaussian, lucy)
  double cutoff = 0.0;               // c (gaussian, lucy; 3 w by default)
  Vec3 lo, hi;                       // the grid's corners (the box by default)
  std::array<int, 3> n{1, 1, 1};     // points along x, y, z (1 on averaged axes)
  std::array<bool, 3> averaged{false, false, false};
  // A cylindrical grid (analysis/cg_cylinder.hpp) about the vertical line through axis_x,
  // axis_y: lo and hi then hold r and z (lo.x = r_lo, lo.z = z_lo; y unused), n and averaged
  // are along r, theta, z.
  bool cylindrical = false;
  double axis_x = 0.0, axis_y = 0.0;
  double interval = 0.0;           // between writes
  int average_every = 0;           // > 0: each write is the mean over every k-th step since the
                                   // last (a time average); 0: the state at the write
  bool contacts = true;            // the contact fields too (recorded on the sample's step)
  std::vector<std::string> fields; // the fields written (all by default)

  // Every field's name, in the order the files give them.
  static const std::vector<std::string>& field_names() {
    static const std::vector<std::string> names{"density",
                                                "number_density",
                                                "volume_fraction",
                                                "momentum",
                                                "velocity",
                                                "kinetic_stress",
                                                "contact_stress",
                                                "stress",
                                                "wall_force_density",
                                                "temperature",
                                                "coordination",
                                                "fabric",
                                                "kinetic_energy_density",
                                                "elastic_energy_density",
                                                "dissipation_rate_density",
                                                "relaxation_energy_density",
                                                "wall_power_density"};
    return names;
  }
};

} // namespace yuxi
