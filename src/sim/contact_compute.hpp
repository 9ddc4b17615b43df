// The contact computation of a simulation, one part of it: the scene's contact law, the pair
// loop templated on its model (sim/contact_forces.hpp), every contact's history, the tally of
// the last force evaluation and the optional per-contact record. One std::visit per call picks
// the model; everything below it is monomorphic.
#pragma once

#include "contact/contact_history.hpp"
#include "contact/contact_model.hpp"
#include "core/near_pairs.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "scene/plane_wall.hpp"
#include "scene/shaped_wall.hpp"
#include "sim/contact_forces.hpp"
#include "sim/contact_tally.hpp"
#include "sim/near_wall_elements.hpp"
#include "sim/simulation_config.hpp"

#include <cstdint>
#include <variant>
#include <vector>

namespace yuxi {

class ContactCompute {
public:
  explicit ContactCompute(AnyContactLaw law, Backend backend = Backend::cpu);
  ContactCompute(const ContactCompute&) = delete;
  ContactCompute& operator=(const ContactCompute&) = delete;

  const AnyContactLaw& law() const { return law_; }
  // Materials of the law's table, and whether it has coefficients for a pair of them.
  std::size_t n_materials() const { return n_materials_; }
  bool has_pair(std::uint8_t a, std::uint8_t b) const;

  // Every contact's state under the model (aligned with the neighbour list), through the
  // model-independent interface.
  ContactStates& history() { return *history_; }
  const ContactStates& history() const { return *history_; }

  // The tally of the last force evaluation (this rank's), and the per-contact record.
  ContactTally& tally() { return tally_; }
  const ContactTally& tally() const { return tally_; }
  void record_contacts(bool on) { record_.enabled = on; }
  const ContactRecord& record() const { return record_; }
  // This rank's loads of the planes at the last evaluation, and its contacts with shaped walls
  // that began already deep.
  const std::vector<WallLoad>& plane_loads() const;
  // The loads another engine's last evaluation gave (Simulation::take_engine_state).
  void set_plane_loads(std::vector<WallLoad> loads);
  const DeepStarts& deep_starts() const;

  // The contacts of listed pairs (PairSet) and, but for PairSet::ghost, of grains with planes
  // (ContactForces::compute). `near`: the near pairs, where they hold. `particles_still`: no
  // wall particle moves. dt 0 advances no spring (a setup pass).
  void compute_pairs(ParticleView s, const NeighborList& list, const NearPairs* near,
                     const std::vector<PlaneWall>& planes, double t, double dt,
                     bool particles_still, PairSet set);
  // The contacts of grains with shaped walls (ContactForces::compute_walls).
  void compute_shaped(ParticleView s, const NeighborList& list, const NearWallElements* near,
                      const std::vector<ShapedWall>& shaped, double t, double dt,
                      std::vector<WallLoad>& loads, std::vector<ElementForce>& elements);

  // After a list build (the history restored): sizes the wall loop's buffers, and `elements`,
  // for the new list's candidates, so that no step allocates until the next list build.
  void size_for(const NeighborList& list, std::vector<ElementForce>& elements);

  // Calls fn(law) with the law's concrete ContactLaw<Model>.
  template <class F> decltype(auto) visit_law(F&& fn) const {
    return std::visit(std::forward<F>(fn), law_);
  }

private:
  template <class> struct ForcesOf;
  template <class... M> struct ForcesOf<std::variant<ContactLaw<M>...>> {
    using type = std::variant<ContactForces<M>...>;
  };
  using Forces = typename ForcesOf<AnyContactLaw>::type;

  AnyContactLaw law_;
  Forces forces_;
  ContactStates* history_; // the contact states of forces_
  std::size_t n_materials_;
  ContactTally tally_;
  ContactRecord record_;
};

} // namespace yuxi
