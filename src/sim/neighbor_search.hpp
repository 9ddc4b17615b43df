// The neighbour search of a simulation, one part of it: the Verlet list of pairs within the
// skin (core/neighbor_list.hpp) with the grains' plane candidates, the near pairs and near wall
// elements that stand for it while they hold (core/near_pairs.hpp, sim/near_wall_elements.hpp),
// and the tracking of displacements that says when they lapse. The grains' candidates against
// shaped walls are listed by the walls part (Walls::list_candidates) into the same list.
#pragma once

#include "core/cell_grid.hpp"
#include "core/near_pairs.hpp"
#include "core/neighbor_list.hpp"
#include "core/particle_store.hpp"
#include "scene/plane_wall.hpp"
#include "scene/shaped_wall.hpp"
#include "sim/near_wall_elements.hpp"

#include <cstdint>
#include <vector>

namespace yuxi {

class NeighborSearch {
public:
  // `skin`: the list's reach beyond touching [length]. `box`: positions are rounded at every
  // step, by a few units in the last place of the largest coordinate a particle in it can have.
  NeighborSearch(double skin, const Box& box);

  double skin() const { return skin_; }
  const NeighborList& list() const { return list_; }
  NeighborList& list() { return list_; }
  const NearPairs& near_pairs() const { return near_; }
  const NearWallElements& near_wall_elements() const { return near_walls_; }
  // The near pairs where they hold (else null: the whole list is scanned), and the near wall
  // elements where they were picked with them.
  const NearPairs* held_near_pairs() const { return near_.hold() ? &near_ : nullptr; }
  const NearWallElements* held_near_wall_elements() const {
    return near_.hold() && near_walls_.picked ? &near_walls_ : nullptr;
  }

  // The list of the owned particles and their ghosts, binned on `grid` (its pairs with a ghost
  // first where forces on ghosts go back to another rank), and every grain's planes within
  // reach. The near pairs lapse (they index the old list).
  void build(const ParticleStore& s, const CellGrid& grid, bool ghost_pairs_first,
             const std::vector<PlaneWall>& planes);

  // After each step's collective: `largest` bounds every particle's displacement in the step.
  void note_displacement(double largest);

  // Picks the near pairs again where those held have lapsed and new ones would last a few
  // steps; drops them where they would not. `slots`: the contact states' slot of each listed
  // pair. `near_fraction`: the margin's most as a fraction of the skin.
  void refresh_near(const ParticleStore& s, const std::uint32_t* slots,
                    const std::vector<ShapedWall>& shaped, double near_fraction);

  std::size_t memory_bytes() const;

private:
  double skin_;
  NeighborList list_;
  NearPairs near_;
  NearWallElements near_walls_;     // picked with near_
  double last_displacement_ = 0.0;  // largest displacement of a particle in the last step
  double position_round_off_ = 0.0; // bound on the round-off of one step's displacement
};

} // namespace yuxi
