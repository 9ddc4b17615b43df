#include "core/neighbor_list.hpp"

namespace yuxi {
namespace {

bool within(const ParticleStore& s, std::size_t i, std::size_t j, double range) {
  const double cut = s.radius[i] + s.radius[j] + range;
  return norm2(s.x[i] - s.x[j]) < cut * cut;
}

bool both_walls(const ParticleStore& s, std::size_t i, std::size_t j) {
  return s.kind[i] == Kind::wall && s.kind[j] == Kind::wall;
}

// The owned-ghost rule: the pair belongs to the copy whose owned particle has the lower gid.
bool ghost_pair_is_ours(const ParticleStore& s, std::size_t i, std::size_t ghost) {
  return s.gid[i] < s.gid[ghost];
}

} // namespace

void build_neighbor_list(const ParticleStore& s, const CellGrid& grid, double range,
                         NeighborList& list) {
  const std::size_t n = s.n_owned();
  list.offsets.assign(n + 1, 0);
  list.partners.clear();
  const auto dims = grid.dims();
  for (std::uint32_t i = 0; i < n; ++i) {
    list.offsets[i] = static_cast<std::uint32_t>(list.partners.size());
    const auto c = grid.cell_of(s.x[i]);
    auto consider = [&](std::uint32_t j, bool owned_allowed) {
      if (j == i || both_walls(s, i, j)) return;
      const bool ghost = j >= n;
      if (ghost ? !ghost_pair_is_ours(s, i, j) : !owned_allowed) return;
      if (within(s, i, j, range)) list.partners.push_back(j);
    };
    // The cell itself: owned partners after i only.
    for (std::uint32_t j : grid.particles_in(grid.linear(c[0], c[1], c[2]))) consider(j, j > i);
    auto visit = [&](const std::array<std::array<int, 3>, 13>& shell, bool owned_allowed) {
      for (const auto& o : shell) {
        const int x = c[0] + o[0], y = c[1] + o[1], z = c[2] + o[2];
        if (x < 0 || y < 0 || z < 0 || x >= dims[0] || y >= dims[1] || z >= dims[2]) continue;
        for (std::uint32_t j : grid.particles_in(grid.linear(x, y, z))) consider(j, owned_allowed);
      }
    };
    visit(CellGrid::half_shell(), true);
    if (s.n_ghost() > 0) visit(CellGrid::lower_shell(), false);
  }
  list.offsets[n] = static_cast<std::uint32_t>(list.partners.size());
}

void build_neighbor_list_brute_force(const ParticleStore& s, double range, NeighborList& list) {
  const std::size_t n = s.n_owned();
  list.offsets.assign(n + 1, 0);
  list.partners.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    list.offsets[i] = static_cast<std::uint32_t>(list.partners.size());
    for (std::uint32_t j = 0; j < s.size(); ++j) {
      if (j == i || both_walls(s, i, j)) continue;
      if (j < n ? j < i : !ghost_pair_is_ours(s, i, j)) continue;
      if (within(s, i, j, range)) list.partners.push_back(j);
    }
  }
  list.offsets[n] = static_cast<std::uint32_t>(list.partners.size());
}

} // namespace yuxi
