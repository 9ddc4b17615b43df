#include "core/near_pairs.hpp"

#include "core/overlap_scan.hpp"

namespace yuxi {

void pick_near_pairs(const Vec3* x, const double* radius, const NeighborList& list,
                     const std::uint32_t* slot, double margin, NearPairs& near) {
  const auto n = static_cast<std::uint32_t>(list.n_pairs());
  const std::uint32_t* row = list.rows.data();
  const std::uint32_t* partner = list.partners.data();
  near.pairs.clear(); // (its capacity stays: the next pick needs about as much)
  const auto near_enough = [&](std::uint32_t p) {
    const std::uint32_t i = row[p], j = partner[p];
    const Vec3 d = x[i] - x[j];
    const double reach = radius[i] + radius[j] + margin;
    return static_cast<std::uint32_t>((norm2(d) < reach * reach) | (slot[p] != no_slot));
  };
  // The ghost pairs first (a short list), then the pairs of owned particles.
  for (const std::uint32_t p : list.ghost_pairs)
    if (near_enough(p)) near.pairs.push_back(p);
  near.n_ghost = static_cast<std::uint32_t>(near.pairs.size());
  const std::uint32_t partner_limit = list.owned_partner_limit();
  // Chunk by chunk, each pair written at the cursor and kept by advancing it, like the overlap
  // scan: the outcome follows no pattern a branch predictor could learn.
  constexpr std::uint32_t chunk = 256;
  std::uint32_t kept[chunk];
  for (std::uint32_t begin = 0; begin < n; begin += chunk) {
    const std::uint32_t end = begin + chunk < n ? begin + chunk : n;
    std::uint32_t k = 0;
    for (std::uint32_t p = begin; p < end; ++p) {
      kept[k] = p;
      k += near_enough(p) & static_cast<std::uint32_t>(partner[p] < partner_limit);
    }
    near.pairs.insert(near.pairs.end(), kept, kept + k);
  }
  near.margin = margin;
  near.moved = 0.0;
  near.picked = true;
}

} // namespace yuxi
