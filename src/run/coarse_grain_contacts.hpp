// The contacts of a simulation's last force evaluation as coarse-graining's contacts
// (analysis/coarse_grain.hpp): needs Simulation::record_contacts(true) before that evaluation.
#pragma once

#include "analysis/coarse_grain.hpp"
#include "sim/simulation.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace yuxi {

// This rank's touching contacts, each once over the ranks (a pair is listed on one rank; its
// partner may be a ghost: an image, or another rank's grain). A wall particle is a wall: the
// grain is then the contact's grain, whichever the list made the row. Throws std::runtime_error
// where contacts are not recorded. grain_of, where given, is each owned particle's place among the
// coarse-grained grains (-1 for a wall particle): the contacts then name their grains by it.
std::vector<analysis::CgContact> coarse_grain_contacts(const Simulation& sim,
                                                       std::span<const std::int64_t> grain_of = {});

// A simulation's grains (owned, never wall particles) and, where recorded, its contacts, as
// coarse-graining's input. Kept between samples, so that its arrays are reused.
struct CoarseGrainInput {
  std::vector<Vec3> x, v;
  std::vector<double> mass, volume;
  std::vector<std::int64_t> grain_of; // each owned particle's place among the grains, or -1
  std::vector<analysis::CgContact> contacts;

  // The grains now, and the contacts of the last force evaluation where they were recorded.
  void gather(const Simulation& sim);
  analysis::CgGrains grains() const { return {x, v, mass, volume}; }
};

} // namespace yuxi
