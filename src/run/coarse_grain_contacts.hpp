// The contacts of a simulation's last force evaluation as coarse-graining's contacts
// (analysis/coarse_grain.hpp): needs Simulation::record_contacts(true) before that evaluation.
#pragma once

#include "analysis/coarse_grain.hpp"
#include "sim/simulation.hpp"

#include <vector>

namespace yuxi {

// This rank's touching contacts, each once over the ranks (a pair is listed on one rank; its
// partner may be a ghost: an image, or another rank's grain). A wall particle is a wall: the
// grain is then the contact's grain, whichever the list made the row. Throws std::runtime_error
// where contacts are not recorded.
std::vector<analysis::CgContact> coarse_grain_contacts(const Simulation& sim);

} // namespace yuxi
