#include "analysis/grain_energy.hpp"

#include <stdexcept>
#include <string>

namespace yuxi::analysis {

std::vector<double> grain_elastic_energy(std::size_t n_grains,
                                         std::span<const ContactEnergy> contacts) {
  std::vector<double> energy(n_grains, 0.0);
  const auto give_half = [&](std::size_t k, double e) {
    if (k == wall_partner) return;
    if (k >= n_grains)
      throw std::out_of_range("grain_elastic_energy: grain index " + std::to_string(k) + " of " +
                              std::to_string(n_grains));
    energy[k] += 0.5 * e;
  };
  for (const auto& c : contacts) {
    give_half(c.i, c.energy);
    give_half(c.j, c.energy);
  }
  return energy;
}

std::vector<double> grain_translational_energy(std::span<const double> masses,
                                               std::span<const Vec3> velocities) {
  if (masses.size() != velocities.size())
    throw std::invalid_argument("grain_translational_energy: masses and velocities differ in size");
  std::vector<double> e(masses.size());
  for (std::size_t k = 0; k < e.size(); ++k) e[k] = 0.5 * masses[k] * norm2(velocities[k]);
  return e;
}

std::vector<double> grain_rotational_energy(std::span<const double> inertias,
                                            std::span<const Vec3> angular_velocities) {
  if (inertias.size() != angular_velocities.size())
    throw std::invalid_argument(
        "grain_rotational_energy: inertias and angular velocities differ in size");
  std::vector<double> e(inertias.size());
  for (std::size_t k = 0; k < e.size(); ++k)
    e[k] = 0.5 * inertias[k] * norm2(angular_velocities[k]);
  return e;
}

std::vector<double> grain_kinetic_energy(std::span<const double> masses,
                                         std::span<const Vec3> velocities,
                                         std::span<const double> inertias,
                                         std::span<const Vec3> angular_velocities) {
  if (masses.size() != inertias.size())
    throw std::invalid_argument("grain_kinetic_energy: masses and inertias differ in size");
  std::vector<double> e = grain_translational_energy(masses, velocities);
  const std::vector<double> rot = grain_rotational_energy(inertias, angular_velocities);
  for (std::size_t k = 0; k < e.size(); ++k) e[k] += rot[k];
  return e;
}

} // namespace yuxi::analysis
