#include "sim/neighbor_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace yuxi {

NeighborSearch::NeighborSearch(double skin, const Box& box) : skin_(skin) {
  for (int a = 0; a < 3; ++a)
    position_round_off_ = std::max({position_round_off_, std::abs(box.lo[a]), std::abs(box.hi[a])});
  position_round_off_ *= 8.0 * std::numeric_limits<double>::epsilon();
}

void NeighborSearch::build(const ParticleStore& s, const CellGrid& grid, bool ghost_pairs_first,
                           const std::vector<PlaneWall>& planes) {
  build_neighbor_list(s, grid, skin_, list_);
  list_.index_ghost_pairs(ghost_pairs_first);
  near_.picked = false; // (they index the old list)
  near_walls_.picked = false;
  list_.planes.clear();
  for (std::uint32_t i = 0; i < s.n_owned(); ++i) {
    if (!s.is_grain(i)) continue;
    for (std::uint32_t p = 0; p < planes.size(); ++p)
      if (planes[p].distance_at_rest(s.x[i]) < s.radius[i] + skin_ + planes[p].max_excursion())
        list_.planes.push_back({i, p});
  }
}

void NeighborSearch::note_displacement(double largest) {
  // The bound on every particle's displacement since the near pairs were picked, with room for
  // the round-off of positions.
  last_displacement_ = largest;
  near_.moved += last_displacement_ + position_round_off_;
}

void NeighborSearch::refresh_near(const ParticleStore& s, const std::uint32_t* slots,
                                  const std::vector<ShapedWall>& shaped, double near_fraction) {
  if (near_.hold()) return;
  near_.picked = false;
  near_walls_.picked = false;
  // The margin leaves room for about `lasting` steps at the last step's pace (a pick costs
  // about one scan of the whole list; a dense packing has many pairs just short of touching,
  // so a wider margin keeps many more), and at most a fraction of the skin. Near pairs that
  // would last fewer than `min_steps` steps are not worth picking: the whole list is scanned.
  constexpr double lasting = 16.0, min_steps = 4.0;
  const double pace = last_displacement_ + position_round_off_;
  const double margin = std::min(near_fraction * skin_, 2.0 * lasting * pace);
  if (!(margin > 0.0) || 2.0 * min_steps * pace >= margin) return;
  pick_near_pairs(s.x.data(), s.radius.data(), list_, slots, margin, near_);
  if (!list_.walls.empty()) pick_near_wall_elements(s, list_, shaped, margin, near_walls_);
}

std::size_t NeighborSearch::memory_bytes() const {
  return list_.memory_bytes() + near_.memory_bytes() + near_walls_.memory_bytes();
}

} // namespace yuxi
