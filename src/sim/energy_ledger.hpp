// The energy ledger of a simulation, one part of it: this rank's cumulative books (dissipated,
// wall work, removed, inserted, gravity's work along periodic axes), the balance at the start,
// the books a list build left due for checking, and this rank's health error of the last force
// evaluation. It computes the instantaneous totals from the particles and judges a gain of
// energy (docs/ARCHITECTURE.md, "Energy books"); the simulation formats the diagnosis.
#pragma once

#include "core/particle_energy.hpp"
#include "core/particle_store.hpp"
#include "sim/contact_tally.hpp"
#include "sim/energy_books.hpp"
#include "sim/simulation_config.hpp"

#include <optional>
#include <string>
#include <utility>

namespace yuxi {

// J w^2 / 2 of particle i (core/particle_energy.hpp).
inline double rotational_energy(const ParticleStore& s, std::size_t i) {
  return rotational_energy(s.w[i], s.inv_inertia[i]);
}

// Kinetic plus gravitational energy of particle i under gravity's potential part g_potential.
inline double mechanical_energy(const ParticleStore& s, std::size_t i, const Vec3& g_potential) {
  return mechanical_energy(s.mass[i], s.x[i], s.v[i], s.w[i], s.inv_inertia[i], g_potential);
}

class EnergyLedger {
public:
  // This rank's cumulative books (the instantaneous totals are parts()'s).
  EnergyBooks& books() { return books_; }
  const EnergyBooks& books() const { return books_; }
  // The books' balance at the start of the run (the blow-up diagnosis measures from it).
  double initial_balance() const { return initial_balance_; }
  void set_initial_balance(double b) { initial_balance_ = b; }

  // This rank's part of the books now: the cumulative books with the grains' energies and the
  // contacts' of the last force evaluation (`tally`).
  EnergyBooks parts(const ParticleStore& s, const SimulationConfig& config,
                    const ContactTally& tally, std::int64_t step, double time) const;

  // The books of a list build, summed and checked at the next collective (a collective there
  // would make every rank wait for the slowest list build, and again for the slowest pairs).
  void leave_due(const EnergyBooks& parts) { due_ = parts; }
  std::optional<EnergyBooks> take_due() { return std::exchange(due_, std::nullopt); }

  // A gain of energy that an unstable integration makes: more than 10 % of the energy in play
  // since the start. The books (mechanical + dissipated + removed - wall work) stay constant up
  // to the integrator's error, about 1 % in violent runs at t_c/dt = 20.
  struct Gain {
    double gained = 0.0, in_play = 0.0;
  };
  std::optional<Gain> unstable_gain(const EnergyBooks& summed) const;

  // This rank's diagnosis of the last force evaluation ("" if sound): an overlap beyond the
  // limit. The next collective stops every rank with it.
  const std::string& health_error() const { return health_error_; }
  void set_health_error(std::string error) { health_error_ = std::move(error); }

private:
  EnergyBooks books_;
  double initial_balance_ = 0.0;
  std::optional<EnergyBooks> due_;
  std::string health_error_;
};

} // namespace yuxi
