// Where coarse-grained fields are evaluated: a Cartesian grid that resolves 1, 2 or 3 axes and
// averages over the others (docs/coarse-graining.md, "Grids").
//
// Along a resolved axis the n points stand at the centres of n equal cells of [lo, hi]:
// lo + (k + 1/2) h, h = (hi - lo) / n (the cells are the bins of plain binning). An averaged axis
// has one point; the fields are averages over [lo, hi] along it, of the grains (and the parts of
// branches) within it. Along a periodic axis that the grid spans exactly, the points wrap and
// every grain counts.
// Points are stored with x fastest: index = (k * ny + j) * nx + i.
#pragma once

#include "core/vec3.hpp"

#include <array>
#include <cstddef>

namespace yuxi::analysis {

struct CgGrid {
  Vec3 lo, hi;
  std::array<int, 3> n{1, 1, 1}; // points along each axis (1 where averaged)
  std::array<bool, 3> averaged{false, false, false};
  std::array<bool, 3> periodic{false, false, false}; // resolved axes whose points wrap

  // Throws std::invalid_argument naming the axis and the problem: hi <= lo, n < 1, an averaged
  // axis with n != 1, or no resolved axis.
  void check() const;

  int dimension() const; // the resolved axes, 1 to 3
  double spacing(int axis) const { return (hi[axis] - lo[axis]) / n[axis]; }
  double coordinate(int axis, int k) const { return lo[axis] + (k + 0.5) * spacing(axis); }
  std::size_t size() const { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }
  std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * n[1] + j) * n[0] + i;
  }
  // The product of the averaged axes' lengths (1 where none): the fields divide by it.
  double averaged_extent() const;
  // A cell's volume: the resolved spacings times the averaged extent.
  double cell_volume() const;
};

} // namespace yuxi::analysis
