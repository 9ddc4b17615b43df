// Energies per grain, for maps and probability densities (Li & Cai 2008, Figs. 8-10).
//
// Elastic: the energy a contact stores in its springs (k_n delta^2/2 + k_t |s_t|^2/2 for the
// linear model) is shared half and half by its two partners. A grain touching a wall particle or
// a flat wall gets its half; the wall's half is not given to any grain, so the per-grain
// energies sum to (grain-grain contacts' energy) + (grain-wall contacts' energy) / 2.
// Kinetic: m v^2 / 2 (translational) + J w^2 / 2 (rotational; J a scalar, solid spheres).
// Energies in the scene's units (m sigma^2 / tau^2 in the basin scenes).
#pragma once

#include "core/vec3.hpp"

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

namespace yuxi::analysis {

// The partner index of a contact with a wall particle or a flat wall.
inline constexpr std::size_t wall_partner = std::numeric_limits<std::size_t>::max();

// One contact: grains i and j (indices into the per-grain arrays) or wall_partner on either
// side, and the elastic energy it stores.
struct ContactEnergy {
  std::size_t i;
  std::size_t j;
  double energy;
};

// Per-grain elastic energy of n_grains grains. Throws std::out_of_range for an index that is
// neither < n_grains nor wall_partner.
std::vector<double> grain_elastic_energy(std::size_t n_grains,
                                         std::span<const ContactEnergy> contacts);

// m_k |v_k|^2 / 2 per grain. Throws std::invalid_argument if the sizes differ.
std::vector<double> grain_translational_energy(std::span<const double> masses,
                                               std::span<const Vec3> velocities);

// J_k |w_k|^2 / 2 per grain. Throws std::invalid_argument if the sizes differ.
std::vector<double> grain_rotational_energy(std::span<const double> inertias,
                                            std::span<const Vec3> angular_velocities);

// Translational + rotational per grain. Throws std::invalid_argument if the sizes differ.
std::vector<double> grain_kinetic_energy(std::span<const double> masses,
                                         std::span<const Vec3> velocities,
                                         std::span<const double> inertias,
                                         std::span<const Vec3> angular_velocities);

} // namespace yuxi::analysis
