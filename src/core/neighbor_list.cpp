#include "core/neighbor_list.hpp"

#include <algorithm>
#include <array>
#include <cstddef>

namespace yuxi {
namespace {

bool within(const ParticleStore& s, std::size_t i, std::size_t j, double range) {
  const double cut = s.radius[i] + s.radius[j] + range;
  return norm2(s.x[i] - s.x[j]) < cut * cut;
}

// Two wall particles, or two members of one clump: never a contact.
bool never_touch(const ParticleStore& s, std::size_t i, std::size_t j) {
  return (s.kind[i] == Kind::wall && s.kind[j] == Kind::wall) ||
         (s.body[i] >= 0 && s.body[i] == s.body[j]);
}

} // namespace

void build_neighbor_list(const ParticleStore& s, const CellGrid& grid, double range,
                         NeighborList& list) {
  const std::size_t n = s.n_owned();
  list.offsets.assign(n + 1, 0);
  list.partners.clear();
  const auto dims = grid.dims();
  const bool has_ghosts = s.n_ghost() > 0;
  // Where a cell and all its neighbours lie inside the grid, the neighbours are at fixed
  // offsets of the linear cell index: no bounds checks.
  std::array<std::ptrdiff_t, 13> upper{}, lower{};
  for (std::size_t k = 0; k < 13; ++k) {
    const auto& o = CellGrid::half_shell()[k];
    upper[k] =
        o[0] + static_cast<std::ptrdiff_t>(dims[0]) * (o[1] + std::ptrdiff_t{dims[1]} * o[2]);
    lower[k] = -upper[k];
  }
  const auto on_layer = [&](const std::array<int, 3>& c, int depth) {
    for (int a = 0; a < 3; ++a)
      if (c[a] < depth || c[a] >= dims[a] - depth) return true;
    return false;
  };
  // Ghosts sit in the grid's outer layer of cells (the halo copies particles within one cell
  // edge of a face, and the layer is one cell deep), so only cells next to that layer have
  // ghosts in their lower half shell. Checked here: otherwise every cell visits it.
  bool ghosts_outside = true;
  for (std::size_t j = n; j < s.size() && ghosts_outside; ++j)
    ghosts_outside = on_layer(grid.cell_of(s.x[j]), 1);
  // Candidates are written at the cursor unconditionally and kept by advancing it: about one
  // candidate in five is kept, in no pattern a branch predictor could learn, so a branch on the
  // outcome would be mispredicted more often than the whole test costs. Room for every
  // candidate of a cell is made before the cell is scanned.
  const Vec3* x = s.x.data();
  const double* radius = s.radius.data();
  const Kind* kind = s.kind.data();
  const GlobalId* body = s.body.data();
  // (members of clumps are rare: a store without them skips the test)
  const bool has_members = std::any_of(body, body + s.size(), [](GlobalId b) { return b >= 0; });
  std::size_t kept = 0;
  list.partners.resize(std::max<std::size_t>(list.partners.capacity(), 64));
  // (Grown by a quarter at a time, reserved exactly: resize() alone would double the memory.)
  const auto make_room = [&](std::size_t candidates) {
    if (kept + candidates <= list.partners.size()) return;
    const std::size_t grown =
        std::max(list.partners.size() + list.partners.size() / 4, kept + candidates + 64);
    list.partners.reserve(grown);
    list.partners.resize(grown);
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    list.offsets[i] = static_cast<std::uint32_t>(kept);
    const Vec3 xi = x[i];
    const double ri = radius[i];
    const bool wall_i = kind[i] == Kind::wall;
    const GlobalId body_i = has_members ? body[i] : GlobalId{-1};
    const auto c = grid.cell_of(xi);
    const auto here = static_cast<std::ptrdiff_t>(grid.linear(c[0], c[1], c[2]));
    // Keeps j when it is near, not a second wall particle nor a member of i's clump, and `ours`
    // (the pair rules: every ghost pair is ours, the halo holding the half shell of ghosts).
    const auto keep_if_near = [&](std::uint32_t j, bool ours) {
      const double cut = ri + radius[j] + range; // as within() adds them
      const bool near = norm2(xi - x[j]) < cut * cut;
      const bool walls = wall_i & (kind[j] == Kind::wall);
      const bool same_body = body_i >= 0 && body[j] == body_i;
      list.partners[kept] = j;
      kept += static_cast<std::size_t>(near & !walls & !same_body & ours);
    };
    // The cell itself: owned partners after i, and every ghost.
    {
      const auto cell = grid.particles_in(static_cast<std::size_t>(here));
      make_room(cell.size());
      for (std::uint32_t j : cell) keep_if_near(j, (j > i) | (j >= n));
    }
    const auto scan = [&](std::size_t cell_index, bool ghosts_only) {
      auto cell = grid.particles_in(cell_index);
      // A cell lists its particles by ascending index, so its ghosts (indices >= n) come
      // last: a ghosts-only visit passes over a cell whose last member is owned (most cells)
      // and skips the owned members of the others.
      if (ghosts_only) {
        if (cell.empty() || cell.back() < n) return;
        cell = cell.subspan(static_cast<std::size_t>(
            std::lower_bound(cell.begin(), cell.end(), static_cast<std::uint32_t>(n)) -
            cell.begin()));
      }
      make_room(cell.size());
      for (std::uint32_t j : cell) keep_if_near(j, true);
    };
    const bool interior = !on_layer(c, 1);
    const auto visit = [&](const std::array<std::array<int, 3>, 13>& shell,
                           const std::array<std::ptrdiff_t, 13>& offset, bool ghosts_only) {
      if (interior) {
        for (const std::ptrdiff_t o : offset) scan(static_cast<std::size_t>(here + o), ghosts_only);
        return;
      }
      for (const auto& o : shell) {
        const int cx = c[0] + o[0], cy = c[1] + o[1], cz = c[2] + o[2];
        if (cx < 0 || cy < 0 || cz < 0 || cx >= dims[0] || cy >= dims[1] || cz >= dims[2]) continue;
        scan(grid.linear(cx, cy, cz), ghosts_only);
      }
    };
    // The upper half shell: every partner; the lower half: ghosts only (owned pairs there are
    // listed from the other side).
    visit(CellGrid::half_shell(), upper, false);
    if (has_ghosts && (!ghosts_outside || on_layer(c, 2)))
      visit(CellGrid::lower_shell(), lower, true);
  }
  list.partners.resize(kept);
  list.offsets[n] = static_cast<std::uint32_t>(kept);
  list.index_rows();
}

void build_neighbor_list_brute_force(const ParticleStore& s, double range, NeighborList& list) {
  const std::size_t n = s.n_owned();
  list.offsets.assign(n + 1, 0);
  list.partners.clear();
  for (std::uint32_t i = 0; i < n; ++i) {
    list.offsets[i] = static_cast<std::uint32_t>(list.partners.size());
    for (std::uint32_t j = 0; j < s.size(); ++j) {
      if (j == i || never_touch(s, i, j)) continue;
      if (j < i) continue; // owned pairs once; every ghost pair (the halo's half shell)
      if (within(s, i, j, range)) list.partners.push_back(j);
    }
  }
  list.offsets[n] = static_cast<std::uint32_t>(list.partners.size());
  list.index_rows();
}

} // namespace yuxi
