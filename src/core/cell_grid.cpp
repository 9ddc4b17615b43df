#include "core/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace yuxi {

CellGrid::CellGrid(const Box& box, double min_edge) {
  if (!(min_edge > 0.0)) throw std::invalid_argument("cell edge must be positive");
  for (int a = 0; a < 3; ++a) {
    const double l = box.length(a);
    if (!(l > 0.0)) throw std::invalid_argument("box has zero or negative extent");
    const int inner = std::max(1, static_cast<int>(std::floor(l / min_edge)));
    edge_[a] = l / inner;
    inv_edge_[a] = 1.0 / edge_[a];
    dims_[a] = inner + 2;
    lo_[a] = box.lo[a] - edge_[a];
  }
  const double cells = static_cast<double>(dims_[0]) * dims_[1] * dims_[2];
  if (cells > 2.0e9) throw std::invalid_argument("cell grid too large (over 2e9 cells)");
  start_.assign(n_cells() + 1, 0);
}

std::array<int, 3> CellGrid::cell_of(const Vec3& p) const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double s = (p[a] - lo_[a]) * inv_edge_[a];
    // NaN compares false everywhere and ends up in cell 0; the caller checks positions.
    c[a] = s >= static_cast<double>(dims_[a] - 1) ? dims_[a] - 1
           : s > 0.0                              ? static_cast<int>(s)
                                                  : 0;
  }
  return c;
}

void CellGrid::bin(std::span<const Vec3> positions) {
  std::fill(start_.begin(), start_.end(), 0u);
  std::vector<std::uint32_t> cell(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    cell[i] = static_cast<std::uint32_t>(cell_index(positions[i]));
    ++start_[cell[i] + 1];
  }
  for (std::size_t c = 0; c < n_cells(); ++c) start_[c + 1] += start_[c];
  members_.resize(positions.size());
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < positions.size(); ++i)
    members_[fill[cell[i]]++] = static_cast<std::uint32_t>(i);
}

const std::array<std::array<int, 3>, 13>& CellGrid::half_shell() {
  static const auto shell = [] {
    std::array<std::array<int, 3>, 13> s{};
    int k = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          // strictly "after" the centre cell in (dz, dy, dx) order
          const bool after = dz > 0 || (dz == 0 && (dy > 0 || (dy == 0 && dx > 0)));
          if (after) s[k++] = {dx, dy, dz};
        }
    return s;
  }();
  return shell;
}

const std::array<std::array<int, 3>, 13>& CellGrid::lower_shell() {
  static const auto shell = [] {
    auto s = half_shell();
    for (auto& o : s) o = {-o[0], -o[1], -o[2]};
    return s;
  }();
  return shell;
}

} // namespace yuxi
