#pragma once

#include "sim/simulation.hpp"

#include <pybind11/pybind11.h>

namespace yuxi::python {

// This rank's touching contacts at the last force evaluation as numpy arrays (sim.contacts()):
// needs Simulation::record_contacts(true) before that evaluation.
pybind11::dict contact_arrays(const Simulation& sim);

// The same contacts as analysis::CgContact's fields, for yuxi.coarse_grain: each contact's grain
// (its centre and volume; the grain, where the list paired a wall particle with a grain), the
// other grain's volume or a wall, the force on the grain, the branch to its centre from the
// other's (the image it touches) or from the wall's contact point, the point, the energy.
pybind11::dict cg_contact_arrays(const Simulation& sim);

} // namespace yuxi::python
