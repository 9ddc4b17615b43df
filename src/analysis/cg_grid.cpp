#include "analysis/cg_grid.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace yuxi::analysis {

void CgGrid::check() const {
  static constexpr const char* names[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const std::string axis = names[a];
    if (!(hi[a] > lo[a]) || !std::isfinite(hi[a] - lo[a]))
      throw std::invalid_argument("coarse-graining grid: along " + axis + ", hi (" +
                                  std::to_string(hi[a]) + ") must exceed lo (" +
                                  std::to_string(lo[a]) + ")");
    if (n[a] < 1)
      throw std::invalid_argument("coarse-graining grid: along " + axis +
                                  ", the number of points must be at least 1 (got " +
                                  std::to_string(n[a]) + ")");
    if (averaged[a] && n[a] != 1)
      throw std::invalid_argument("coarse-graining grid: " + axis +
                                  " is averaged, so it has one point (got " + std::to_string(n[a]) +
                                  ")");
  }
  if (dimension() == 0)
    throw std::invalid_argument("coarse-graining grid: every axis is averaged; resolve one at "
                                "least");
}

int CgGrid::dimension() const {
  return (averaged[0] ? 0 : 1) + (averaged[1] ? 0 : 1) + (averaged[2] ? 0 : 1);
}

double CgGrid::averaged_extent() const {
  double extent = 1.0;
  for (int a = 0; a < 3; ++a)
    if (averaged[a]) extent *= hi[a] - lo[a];
  return extent;
}

double CgGrid::cell_volume() const {
  double volume = averaged_extent();
  for (int a = 0; a < 3; ++a)
    if (!averaged[a]) volume *= spacing(a);
  return volume;
}

} // namespace yuxi::analysis
