#include "analysis/xy_grid.hpp"

#include "analysis/analysis_csv.hpp"

#include <stdexcept>

namespace yuxi::analysis {

XYGrid::XYGrid(Vec3 lo, Vec3 hi, std::size_t nx, std::size_t ny)
    : lo_(lo), hi_(hi), nx_(nx), ny_(ny), dx_(0.0), dy_(0.0) {
  if (nx == 0 || ny == 0) throw std::invalid_argument("XYGrid: nx and ny must be >= 1");
  if (!(hi.x > lo.x) || !(hi.y > lo.y) || !is_finite(lo) || !is_finite(hi))
    throw std::invalid_argument("XYGrid: hi must exceed lo in x and y");
  dx_ = (hi.x - lo.x) / static_cast<double>(nx);
  dy_ = (hi.y - lo.y) / static_cast<double>(ny);
}

std::optional<std::size_t> XYGrid::cell_of(const Vec3& p) const {
  if (!(p.x >= lo_.x && p.x < hi_.x && p.y >= lo_.y && p.y < hi_.y)) return std::nullopt;
  // Rounding may put a point just below hi into column n; it belongs to column n - 1.
  std::size_t i = static_cast<std::size_t>((p.x - lo_.x) / dx_);
  std::size_t j = static_cast<std::size_t>((p.y - lo_.y) / dy_);
  if (i >= nx_) i = nx_ - 1;
  if (j >= ny_) j = ny_ - 1;
  return index(i, j);
}

void write_grid_csv(const std::filesystem::path& path, const XYGrid& grid,
                    std::span<const GridColumn> columns) {
  std::vector<std::string> header{"x", "y"};
  for (const auto& c : columns) {
    if (c.values.size() != grid.size())
      throw std::invalid_argument("write_grid_csv: column '" + c.name + "' has " +
                                  std::to_string(c.values.size()) + " values for " +
                                  std::to_string(grid.size()) + " cells");
    header.push_back(c.name);
  }
  CsvWriter csv(path, std::move(header));
  std::vector<double> row(csv.columns());
  for (std::size_t j = 0; j < grid.ny(); ++j)
    for (std::size_t i = 0; i < grid.nx(); ++i) {
      row[0] = grid.x_center(i);
      row[1] = grid.y_center(j);
      for (std::size_t c = 0; c < columns.size(); ++c)
        row[2 + c] = columns[c].values[grid.index(i, j)];
      csv.row(std::span<const double>(row));
    }
  csv.close();
}

} // namespace yuxi::analysis
