// Cartesian domain decomposition: the box is cut into px x py x pz sub-domains, one per rank,
// by cut planes along each axis. The planes start evenly spaced and are moved by balance() so
// that the slabs along each axis carry equal measured load (particles plus their pairs).
// Ranks on the outer faces of open or walled axes own everything beyond the box on that side,
// so grains thrown out stay owned until the escape policy deals with them.
#pragma once

#include "core/box.hpp"
#include "domain/comm.hpp"

#include <array>
#include <string>
#include <vector>

namespace yuxi {

class Decomposition {
public:
  // `layout`: ranks per axis; zeros are chosen so that sub-domains of the occupied region
  // (`occupied`: its lengths along x, y, z; zeros: the whole box) are as cubic as possible.
  Decomposition(const Box& box, const Comm& comm, std::array<int, 3> layout = {0, 0, 0},
                Vec3 occupied = {});

  const Box& box() const { return box_; }
  std::array<int, 3> dims() const { return dims_; }
  std::array<int, 3> coords() const { return coords_; }
  // This rank's sub-domain [lo, hi) (infinite on outer faces of non-periodic axes).
  Vec3 lo() const { return lo_; }
  Vec3 hi() const { return hi_; }
  // The sub-domain as a box for the cell grid: finite, clipped to the global box.
  Box local_box() const;
  bool owns(const Vec3& x) const;
  // Neighbour rank in direction dir (-1 or +1) along axis, -1 if none.
  int neighbor(int axis, int dir) const { return neighbor_[axis][dir > 0 ? 1 : 0]; }
  // Whether crossing to that neighbour crosses the periodic boundary.
  bool wraps(int axis, int dir) const { return wraps_[axis][dir > 0 ? 1 : 0]; }
  // Narrowest sub-domain width along each axis, over all ranks.
  double min_width(int axis) const;
  const std::vector<double>& cuts(int axis) const { return cuts_[axis]; }
  // Restores cut planes (from a checkpoint written with the same layout).
  void set_cuts(int axis, const std::vector<double>& cuts);

  // Moves the cut planes so that each slab along each axis carries the same share of the
  // summed `cost` of the particles at `positions` (all ranks' values are combined).
  void balance(const std::vector<Vec3>& positions, const std::vector<double>& cost,
               const Comm& comm);
  std::string describe() const;
  // The narrowest slab balance() may make (the ghost cutoff).
  void set_min_slab(double width) { min_slab_ = width; }

private:
  int rank_of(std::array<int, 3> c) const { return (c[2] * dims_[1] + c[1]) * dims_[0] + c[0]; }
  void update_region();

  Box box_;
  std::array<int, 3> dims_{1, 1, 1};
  std::array<int, 3> coords_{0, 0, 0};
  std::array<std::vector<double>, 3> cuts_;
  Vec3 lo_, hi_;
  std::array<std::array<int, 2>, 3> neighbor_{};
  std::array<std::array<bool, 2>, 3> wraps_{};
  double min_slab_ = 0.0;
};

// Ranks per axis for `n` ranks on a region of these lengths: the factorisation with the least
// sub-domain surface.
std::array<int, 3> choose_layout(Vec3 lengths, int n, std::array<int, 3> fixed = {0, 0, 0});

} // namespace yuxi
