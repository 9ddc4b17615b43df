// The first pass of the pair loop: which listed pairs overlap now.
//
// A granular flow lists several near misses per touching contact (the chute: about six), in no
// order a branch predictor could learn, so the test |x_i - x_j| < a_i + a_j decides nothing by
// branching: every pair is written at the cursor and the cursor advances past those that pass.
// The contact law then runs on those alone. The pairs are scanned as one flat range (the row of
// each pair is listed beside it), with no loop per row: rows are short (three or four pairs)
// and their ends would be branches too. (Gathering four pairs per AVX2 instruction instead was
// measured slower than this loop.)
#pragma once

#include "core/vec3.hpp"

#include <cstdint>

namespace yuxi {

// Slot of a listed pair that holds no contact state (ContactHistory::pair_slot).
inline constexpr std::uint32_t no_slot = 0xFFFFFFFFu;

// A partner limit that passes no pair over (scan_overlaps()).
inline constexpr std::uint32_t every_partner = 0xFFFFFFFFu;

struct OverlapScanCounts {
  std::uint32_t touching = 0; // pairs written to `touching`
  std::uint32_t parted = 0;   // pairs written to `parted`
};

// Scans the listed pairs p in [begin, end): pair p joins particle row[p] to partner[p]. Writes,
// in ascending order, to `touching` the pairs that overlap, and to `parted` those that do not
// but still hold a contact state (slot[p] != no_slot): contacts that have just come apart.
// Pairs whose partner is at or above `partner_limit` are passed over (the ghost pairs, computed
// apart: NeighborList::ghost_pairs). Each output needs room for end - begin entries.
OverlapScanCounts scan_overlaps(const Vec3* x, const double* radius, const std::uint32_t* row,
                                const std::uint32_t* partner, const std::uint32_t* slot,
                                std::uint32_t begin, std::uint32_t end, std::uint32_t partner_limit,
                                std::uint32_t* touching, std::uint32_t* parted);

// The same over the pairs pairs[begin], ..., pairs[end - 1] (ascending indices into the list:
// the near pairs, core/near_pairs.hpp).
OverlapScanCounts scan_overlaps(const Vec3* x, const double* radius, const std::uint32_t* row,
                                const std::uint32_t* partner, const std::uint32_t* slot,
                                const std::uint32_t* pairs, std::uint32_t begin, std::uint32_t end,
                                std::uint32_t* touching, std::uint32_t* parted);

} // namespace yuxi
