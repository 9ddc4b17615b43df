// The sizes a simulation's decomposition and linked cells are made for, from its particles.
#pragma once

#include "core/box.hpp"
#include "core/particle_store.hpp"
#include "domain/comm.hpp"
#include "sim/simulation_config.hpp"

#include <string>

namespace yuxi {

// Lengths of the region the particles occupy (the whole box along periodic axes, and where
// there is none), for the choice of the rank layout: a tall box over a shallow bed is cut
// across the bed, not through it. Over every rank's owned particles where `comm` is given
// (collective), else over those of `s`.
Vec3 occupied_lengths(const Box& box, const ParticleStore& s, const Comm* comm = nullptr);

// The linked cells' edge [length]: the largest contact distance (`reach`, or the scene's least)
// plus the skin, or the scene's cell size, which may shorten the skin in `c` to fit. Throws
// std::invalid_argument where the cell size is below the reach.
double cell_edge_for(SimulationConfig& c, double reach);

// Why a sphere of `radius` added to a running simulation does not fit its linked cells (edge
// `cell_edge`, skin `skin`), and what the scene must say for it to: "" where it fits.
std::string cells_too_small_for(double radius, double cell_edge, double skin);

} // namespace yuxi
