// Elastic energy per owned particle at a simulation's last force evaluation: half of each
// contact's stored energy to each partner, flat walls keeping theirs
// (analysis/grain_energy.hpp; Li & Cai 2008, Fig. 8).
#pragma once

#include "sim/simulation.hpp"

#include <vector>

namespace yuxi {

// Needs Simulation::record_contacts(true) during that evaluation (throws std::logic_error
// otherwise). Collective: the halves of pairs with a ghost go back to the ghosts' owners.
std::vector<double> particle_elastic_energy(const Simulation& sim);

} // namespace yuxi
