#include "analysis/column_sum.hpp"

#include "analysis/analysis_csv.hpp"

#include <limits>
#include <stdexcept>

namespace yuxi::analysis {

GridField column_sum(const XYGrid& grid, std::span<const Vec3> positions,
                     std::span<const double> values) {
  if (positions.size() != values.size())
    throw std::invalid_argument("column analysis: positions and values differ in size");
  GridField sum{grid, std::vector<double>(grid.size(), 0.0)};
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (!(positions[k].z < std::numeric_limits<double>::infinity())) continue; // NaN or +inf
    if (const auto cell = grid.cell_of(positions[k])) sum.values[*cell] += values[k];
  }
  return sum;
}

void write_column_sum_csv(const std::filesystem::path& path, const GridField& sum,
                          const std::string& name) {
  const GridColumn column{name, sum.values};
  write_grid_csv(path, sum.grid, std::span<const GridColumn>(&column, 1));
}

} // namespace yuxi::analysis
