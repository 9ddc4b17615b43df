#pragma once

#include "io/scene.hpp"
#include "sim/simulation.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <span>
#include <string>
#include <vector>

namespace yuxi::python {

// This rank's clumps as numpy arrays (sim.clumps(); docs/python.md): id (the id of member 0;
// member k has id + k), shape (the index of the scene's [[shape]], -1: none), position (the
// centre of mass), velocity, orientation (the unit quaternion w, x, y, z that turns the
// principal frame onto the lab's), angular_velocity (lab frame), mass, inertia (the principal
// moments, ascending), members (how many), force and torque (at the last force evaluation).
pybind11::dict clump_arrays(const Simulation& sim);

// The [[shape]] of that name as a dict (sim.shape(); docs/python.md): centres (k, 3) and radii
// of the members in the principal frame, volume, inertia_per_density, bounding_radius, frame
// (w, x, y, z: the principal frame onto the table's) and centre (of mass, in the table's frame).
// Raises ValueError naming the scene's shapes where none has that name.
pybind11::dict shape_dict(const Scene& scene, const std::string& name);

// Rows of four numbers (w, x, y, z) as unit quaternions, each made unit where within 1e-6 of
// it; ValueError naming `call` and the row that is not.
std::vector<Quaternion> unit_quaternions(std::span<const double> rows, const char* call);

using DoubleRows = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;

// The clumps that sim.add_clumps() asks for, made (make_clump(), first id 0): of the scene's
// [[shape]] `shape`, each scaled by its `scale`, with the density of `material`; centres of mass
// `x` (n, 3), orientations `q` (n, 4: w, x, y, z, made unit where within 1e-6 of it) that turn
// the shape as its table writes it onto the lab (`principal`: its principal frame, as
// sim.clumps() gives them), velocities `v` and angular velocities `w` (n, 3). Raises ValueError
// naming the argument and the row that is wrong.
std::vector<PlacedClump> placed_clumps(const Scene& scene, const std::string& shape,
                                       const DoubleRows& x, const DoubleRows& q,
                                       const DoubleRows& v, const DoubleRows& w,
                                       const DoubleRows& scale, const std::string& material,
                                       bool principal);

} // namespace yuxi::python
