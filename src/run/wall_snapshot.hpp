// The shaped walls of a simulation as one triangle surface for its snapshots (io/vtk_walls.hpp):
// every mesh and cylinder active at the simulation's time, meshes loaded with the forces of the
// last force evaluation.
#pragma once

#include "io/vtk_walls.hpp"
#include "sim/simulation.hpp"

namespace yuxi {

// Collective (the forces are summed over the ranks); the same on every rank.
WallSurface wall_surface(const Simulation& sim);

} // namespace yuxi
