#include "run/particle_elastic_energy.hpp"

#include "analysis/grain_energy.hpp"

#include <stdexcept>

namespace yuxi {

std::vector<double> particle_elastic_energy(const Simulation& sim) {
  const ContactRecord& record = sim.contact_record();
  const NeighborList& list = sim.neighbor_list();
  if (!record.enabled) throw std::logic_error("particle_elastic_energy needs contact recording");
  std::vector<analysis::ContactEnergy> contacts;
  contacts.reserve(record.pairs.size() + list.planes.size());
  for (const PairContactRecord& r : record.pairs)
    if (r.elastic != 0.0) contacts.push_back({list.rows[r.pair], list.partners[r.pair], r.elastic});
  for (std::size_t k = 0; k < list.planes.size(); ++k)
    if (record.holds_plane(k) && record.plane_elastic[k] != 0.0)
      contacts.push_back(
          {list.planes[k].particle, analysis::wall_partner, record.plane_elastic[k]});
  // Pairs with a ghost were computed here once; the ghost's half goes back to its owner.
  const ParticleStore& s = sim.particles();
  std::vector<double> e = analysis::grain_elastic_energy(s.size(), contacts);
  sim.halo().reverse_sum(e, sim.comm());
  e.resize(s.n_owned());
  return e;
}

} // namespace yuxi
