// A regular grid of vertical columns over the x-y plane, and a field with one value per column.
//
// Column (i, j) is the half-open cell [lo.x + i dx, lo.x + (i+1) dx) x [lo.y + j dy, ...),
// dx = (hi.x - lo.x) / nx; a point outside [lo, hi) in x or y lies in no column (z is ignored).
// Values are stored with x fastest: index = j * nx + i. Written as long CSV (see
// write_grid_csv) the rows come in this order, so numpy reads a column as
// values.reshape(ny, nx) (row j = one y, column i = one x).
#pragma once

#include "core/vec3.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace yuxi::analysis {

class XYGrid {
public:
  // lo, hi: opposite corners (z ignored), hi > lo in x and y; nx, ny >= 1.
  // Throws std::invalid_argument otherwise.
  XYGrid(Vec3 lo, Vec3 hi, std::size_t nx, std::size_t ny);

  std::size_t nx() const { return nx_; }
  std::size_t ny() const { return ny_; }
  std::size_t size() const { return nx_ * ny_; }
  const Vec3& lo() const { return lo_; }
  const Vec3& hi() const { return hi_; }
  double dx() const { return dx_; }
  double dy() const { return dy_; }
  double x_center(std::size_t i) const { return lo_.x + (static_cast<double>(i) + 0.5) * dx_; }
  double y_center(std::size_t j) const { return lo_.y + (static_cast<double>(j) + 0.5) * dy_; }
  std::size_t index(std::size_t i, std::size_t j) const { return j * nx_ + i; }

  // The index of the column holding p's (x, y), or nothing outside the grid (or for NaN).
  std::optional<std::size_t> cell_of(const Vec3& p) const;

private:
  Vec3 lo_, hi_;
  std::size_t nx_, ny_;
  double dx_, dy_;
};

// One value per column of `grid` (values.size() == grid.size()).
struct GridField {
  XYGrid grid;
  std::vector<double> values;

  double at(std::size_t i, std::size_t j) const { return values[grid.index(i, j)]; }
};

// One named column of a grid CSV.
struct GridColumn {
  std::string name;
  std::span<const double> values; // one per cell, index j * nx + i
};

// Long CSV of fields on one grid: header "x,y,<name>...", one row per cell (x fastest), x and y
// the cell centres. Throws std::invalid_argument if a column's size is not grid.size().
void write_grid_csv(const std::filesystem::path& path, const XYGrid& grid,
                    std::span<const GridColumn> columns);

} // namespace yuxi::analysis
