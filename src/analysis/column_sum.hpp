// Per-grain quantities gathered into the columns of an x-y grid.
//
// column_sum: the sum over z of a per-grain quantity in each column, e.g. the vertically summed
// elastic energy of Li & Cai (2008) Fig. 8 (energy in m sigma^2 / tau^2 per column).
// ColumnAccumulator: sums and grain counts per column for the grains whose centres lie in a
// horizontal slab z0 <= z < z1, accumulated over any number of snapshots; from them the time
// average of the column's total and the mean per grain. (Fig. 9's sections are coarse-grained:
// section_energies.hpp.)
//
// CSV of a column sum (write_column_sum_csv), e.g. analysis/elastic_map_t10.25.csv:
//   x,y,<name>          one row per column, x fastest (numpy: reshape(ny, nx)); <name> e.g.
//                       "elastic"; 0 in empty columns.
#pragma once

#include "analysis/xy_grid.hpp"
#include "core/vec3.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace yuxi::analysis {

// Sum of values[k] over the grains k whose centre positions[k] lies in each column (any z);
// 0 for an empty column. Throws std::invalid_argument if the spans differ in size.
GridField column_sum(const XYGrid& grid, std::span<const Vec3> positions,
                     std::span<const double> values);

// The mean of values[k] over the grains whose centres lie in each column and in
// z0 <= z < z1; NaN for a cell with no grain.
GridField slab_mean(const XYGrid& grid, double z0, double z1, std::span<const Vec3> positions,
                    std::span<const double> values);

class ColumnAccumulator {
public:
  // Cells: the columns of `grid` cut to z0 <= z < z1 (the whole height by default).
  // Throws std::invalid_argument unless z0 < z1.
  explicit ColumnAccumulator(XYGrid grid, double z0 = -std::numeric_limits<double>::infinity(),
                             double z1 = std::numeric_limits<double>::infinity());

  // One snapshot: adds values[k] and a count of one to the cell of each grain inside.
  void add(std::span<const Vec3> positions, std::span<const double> values);

  const XYGrid& grid() const { return grid_; }
  double z0() const { return z0_; }
  double z1() const { return z1_; }
  std::size_t snapshots() const { return snapshots_; }
  const std::vector<double>& sums() const { return sums_; }     // over all snapshots
  const std::vector<double>& counts() const { return counts_; } // grain-snapshots per cell

  GridField sum() const; // total over all snapshots
  // Adds up the accumulators of several processes (each saw its own grains at the same
  // snapshots): `sum_in_place(values, n)` must sum n doubles over them, in place.
  void combine(const std::function<void(double*, int)>& sum_in_place);
  GridField time_mean() const;       // sum / snapshots: time average of the cell's total
  GridField time_mean_count() const; // counts / snapshots: mean number of grains in the cell
  GridField grain_mean() const;      // sum / counts: mean per grain (NaN where counts = 0)

private:
  XYGrid grid_;
  double z0_, z1_;
  std::size_t snapshots_ = 0;
  std::vector<double> sums_, counts_;
};

void write_column_sum_csv(const std::filesystem::path& path, const GridField& sum,
                          const std::string& name);

} // namespace yuxi::analysis
