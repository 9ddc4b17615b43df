// The listed pairs that can touch before the next few steps are over: a second, tighter list
// inside the Verlet list, so that the pair loop's overlap test passes over fewer near misses.
//
// The Verlet list keeps every pair closer than r_i + r_j + skin for as long as no particle has
// moved skin/2. A settled bed or a slow flow lists several pairs per touching contact (the
// settled fish basin, skin 0.5: seven), and the overlap test of each costs as much as a tenth
// of a contact's evaluation. The near pairs are those of the list closer than
// r_i + r_j + margin (margin < skin) when they were picked, and those that still hold a
// contact state. A pair left out was at least margin apart; while every particle has moved
// less than margin/2 since (a bound the step keeps from the largest displacement of each step,
// over all ranks), it cannot touch. So the pair loop finds the same touching pairs, in the
// same order, through the near pairs as through the whole list: the results are the same to
// the bit, whenever the near pairs are picked again.
#pragma once

#include "core/neighbor_list.hpp"
#include "core/vec3.hpp"

#include <cstdint>
#include <vector>

namespace yuxi {

struct NearPairs {
  // Indices into the neighbour list, ascending: those with a ghost partner first where they
  // were picked apart (NeighborList::ghost_pairs), then the rest.
  std::vector<std::uint32_t> pairs;
  std::uint32_t n_ghost = 0; // the pairs with a ghost partner that come first
  double margin = 0.0;       // the gap beyond r_i + r_j they were picked within [length]
  double moved = 0.0;        // bound on any particle's displacement since they were picked [length]
  bool picked = false;

  // Whether no pair left out can touch yet.
  bool hold() const { return picked && 2.0 * moved < margin; }
  std::size_t memory_bytes() const { return pairs.capacity() * sizeof(std::uint32_t); }
};

// Picks the near pairs of `list`: those closer than r_i + r_j + margin, and those whose contact
// state slot (`slot`, aligned with the list; no_slot for none) is taken. Where the list has
// its ghost pairs apart, so do the near pairs.
void pick_near_pairs(const Vec3* x, const double* radius, const NeighborList& list,
                     const std::uint32_t* slot, double margin, NearPairs& near);

} // namespace yuxi
