// Descriptions of a particle and its contacts for the diagnoses of a simulation that stops
// (an overlap beyond the limit, a non-finite state, an escape, a gain of energy).
#pragma once

#include "core/box.hpp"
#include "core/particle_store.hpp"
#include "scene/plane_wall.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace yuxi {

// "grain 12 (radius 0.5) at (x, y, z) with velocity (...), angular velocity (...)"; a clump's
// member "grain 12 (member 2 of clump 10, radius 0.5) ...".
std::string describe_particle(const ParticleStore& s, std::size_t i);

// Every particle that overlaps owned particle i (its own clump's members aside: they never
// touch it), owned (through the nearest periodic image in
// `box`) or a ghost from another rank, each once, and the planes it overlaps at time t; "none"
// where nothing does. The halo holds the ghosts of a half shell only, so partners owned by the
// ranks below are not seen here.
std::string describe_contacts(const ParticleStore& s, const Box& box,
                              const std::vector<PlaneWall>& planes, double t, std::size_t i);

} // namespace yuxi
