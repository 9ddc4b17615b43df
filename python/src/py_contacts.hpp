#pragma once

#include "sim/simulation.hpp"

#include <pybind11/pybind11.h>

namespace yuxi::python {

// This rank's touching contacts at the last force evaluation as numpy arrays (sim.contacts()):
// needs Simulation::record_contacts(true) before that evaluation.
pybind11::dict contact_arrays(const Simulation& sim);

} // namespace yuxi::python
