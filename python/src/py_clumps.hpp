#pragma once

#include "sim/simulation.hpp"

#include <pybind11/pybind11.h>

namespace yuxi::python {

// This rank's clumps as numpy arrays (sim.clumps(); docs/python.md): id (the id of member 0;
// member k has id + k), shape (the index of the scene's [[shape]], -1: none), position (the
// centre of mass), velocity, orientation (the unit quaternion w, x, y, z that turns the
// principal frame onto the lab's), angular_velocity (lab frame), mass, inertia (the principal
// moments, ascending), members (how many), force and torque (at the last force evaluation).
pybind11::dict clump_arrays(const Simulation& sim);

} // namespace yuxi::python
