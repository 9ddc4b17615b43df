#include "analysis/free_surface.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace yuxi::analysis {

GridField free_surface(const XYGrid& grid, std::span<const Vec3> positions,
                       std::span<const double> radii) {
  if (positions.size() != radii.size())
    throw std::invalid_argument("free_surface: positions and radii differ in size");
  GridField surface{grid,
                    std::vector<double>(grid.size(), std::numeric_limits<double>::quiet_NaN())};
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const auto cell = grid.cell_of(positions[k]);
    if (!cell) continue;
    const double top = positions[k].z + radii[k];
    double& h = surface.values[*cell];
    if (std::isnan(h) || top > h) h = top;
  }
  return surface;
}

void write_surface_csv(const std::filesystem::path& path, const GridField& surface) {
  const GridColumn column{"height", surface.values};
  write_grid_csv(path, surface.grid, std::span<const GridColumn>(&column, 1));
}

} // namespace yuxi::analysis
