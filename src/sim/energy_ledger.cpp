#include "sim/energy_ledger.hpp"

#include <cmath>

namespace yuxi {

EnergyBooks EnergyLedger::parts(const ParticleStore& s, const SimulationConfig& config,
                                const ContactTally& tally, std::int64_t step, double time) const {
  const Vec3 g_potential = potential_gravity(config);
  EnergyBooks e = books_;
  e.step = step;
  e.time = time;
  for (std::size_t i = 0; i < s.n_owned(); ++i) {
    if (!s.is_grain(i) || s.body[i] >= 0) continue; // (a clump's books are its body's)
    e.translational += translational_energy(s.mass[i], s.v[i]);
    e.rotational += rotational_energy(s, i);
    e.gravitational -= s.mass[i] * dot(g_potential, s.x[i]);
    ++e.grains;
  }
  e.elastic = tally.elastic;
  e.relaxation = tally.relaxation;
  e.contacts = tally.touching;
  return e;
}

std::optional<EnergyLedger::Gain> EnergyLedger::unstable_gain(const EnergyBooks& e) const {
  const double in_play = std::abs(initial_balance_) + e.dissipated + std::abs(e.wall_work) +
                         e.removed + std::abs(e.mechanical());
  const double gained = e.balance() - initial_balance_;
  if (!(gained <= 0.1 * in_play) && in_play > 0) return Gain{gained, in_play};
  return std::nullopt;
}

} // namespace yuxi
