// The energy books of a simulation at one instant (fish_basin.md section 8: every joule booked).
//
// balance() = mechanical + relaxation + dissipated + removed - wall_work - gravity_work is
// conserved by the exact dynamics: what moving walls and gravity put in is still mechanical
// energy, waits in a relaxation buffer (thermodynamic model), has been dissipated, or left with
// grains removed from the domain.
//
// Along periodic axes gravity has no potential (a grain that wraps around would jump in height),
// so the gravitational energy counts only the components of g along non-periodic axes, and the
// work of the others (a tilted periodic chute) is booked as gravity_work.
#pragma once

#include <cstddef>
#include <cstdint>

namespace yuxi {

struct EnergyReport {
  std::int64_t step = 0;
  double time = 0.0;
  double translational = 0.0; // sum m v^2 / 2 over grains
  double rotational = 0.0;    // sum J w^2 / 2 over grains
  double elastic = 0.0;       // energy stored in contact springs
  double gravitational = 0.0; // sum -m g . x over grains (zero at the origin)
  double relaxation = 0.0;    // energy in contacts' relaxation buffers, on its way to heat
  double dissipated = 0.0;    // cumulative, since the start of the run
  double wall_work = 0.0;     // cumulative work done by moving walls on grains
  double removed = 0.0;       // cumulative mechanical energy of grains removed on escape
  double gravity_work = 0.0;  // cumulative work of gravity along periodic axes
  std::size_t grains = 0;
  std::size_t contacts = 0;
  std::size_t escaped = 0; // grains removed after leaving the domain

  double kinetic() const { return translational + rotational; }
  double mechanical() const { return translational + rotational + elastic + gravitational; }
  double balance() const {
    return mechanical() + relaxation + dissipated + removed - wall_work - gravity_work;
  }
};

} // namespace yuxi
