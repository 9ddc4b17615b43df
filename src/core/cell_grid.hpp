// Linked cells: space is cut into equal boxes whose edge is at least the interaction cutoff,
// so every pair closer than the cutoff lies in the same or in adjacent cells (Li & Cai 2008,
// section 1; Allen & Tildesley, "Computer Simulation of Liquids", 5.3.2).
//
// The grid covers the box plus one layer of cells on every side, which holds the periodic
// ghosts. Positions outside the grid are clamped into its outermost layer; clamping is
// monotone, so two particles closer than one cell edge still land in the same or adjacent cells.
#pragma once

#include "core/box.hpp"
#include "core/vec3.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace yuxi {

class CellGrid {
public:
  // Covers `box` extended by one cell on each side, with cells of edge >= `min_edge`.
  CellGrid(const Box& box, double min_edge);

  // Sorts the given positions into cells (counting sort, stable in particle index).
  void bin(std::span<const Vec3> positions);

  std::array<int, 3> dims() const { return dims_; }
  Vec3 origin() const { return lo_; } // the low corner of the outer layer of cells
  Vec3 edge() const { return edge_; }
  std::size_t n_cells() const { return static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2]; }
  std::array<int, 3> cell_of(const Vec3& p) const;
  std::size_t linear(int ix, int iy, int iz) const {
    return (static_cast<std::size_t>(iz) * dims_[1] + iy) * dims_[0] + ix;
  }
  std::size_t cell_index(const Vec3& p) const {
    const auto c = cell_of(p);
    return linear(c[0], c[1], c[2]);
  }
  // The particles of cell c, by ascending index (the neighbour build relies on it).
  std::span<const std::uint32_t> particles_in(std::size_t c) const {
    return {members_.data() + start_[c], members_.data() + start_[c + 1]};
  }

  // The 13 neighbour offsets of the half shell: (dx, dy, dz) > (0, 0, 0) in lexicographic order
  // of (dz, dy, dx). Together with the cell itself they visit every adjacent pair once.
  static const std::array<std::array<int, 3>, 13>& half_shell();
  // The other 13 neighbours (the negated half shell).
  static const std::array<std::array<int, 3>, 13>& lower_shell();

  std::size_t memory_bytes() const {
    return (start_.capacity() + members_.capacity()) * sizeof(std::uint32_t);
  }

private:
  Vec3 lo_;
  Vec3 edge_;
  Vec3 inv_edge_;
  std::array<int, 3> dims_{};
  std::vector<std::uint32_t> start_;   // n_cells + 1 offsets into members_
  std::vector<std::uint32_t> members_; // particle indices grouped by cell
};

} // namespace yuxi
