#include "analysis/column_sum.hpp"

#include "analysis/analysis_csv.hpp"

#include <cmath>
#include <stdexcept>

namespace yuxi::analysis {

namespace {

void check_sizes(std::span<const Vec3> positions, std::span<const double> values) {
  if (positions.size() != values.size())
    throw std::invalid_argument("column analysis: positions and values differ in size");
}

} // namespace

GridField column_sum(const XYGrid& grid, std::span<const Vec3> positions,
                     std::span<const double> values) {
  ColumnAccumulator acc(grid);
  acc.add(positions, values);
  return acc.sum();
}

GridField slab_mean(const XYGrid& grid, double z0, double z1, std::span<const Vec3> positions,
                    std::span<const double> values) {
  ColumnAccumulator acc(grid, z0, z1);
  acc.add(positions, values);
  return acc.grain_mean();
}

ColumnAccumulator::ColumnAccumulator(XYGrid grid, double z0, double z1)
    : grid_(grid), z0_(z0), z1_(z1), sums_(grid.size(), 0.0), counts_(grid.size(), 0.0) {
  if (!(z0 < z1)) throw std::invalid_argument("ColumnAccumulator: z0 must be below z1");
}

void ColumnAccumulator::add(std::span<const Vec3> positions, std::span<const double> values) {
  check_sizes(positions, values);
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const double z = positions[k].z;
    if (!(z >= z0_ && z < z1_)) continue;
    const auto cell = grid_.cell_of(positions[k]);
    if (!cell) continue;
    sums_[*cell] += values[k];
    counts_[*cell] += 1.0;
  }
  ++snapshots_;
}

void ColumnAccumulator::combine(const std::function<void(double*, int)>& sum_in_place) {
  sum_in_place(sums_.data(), static_cast<int>(sums_.size()));
  sum_in_place(counts_.data(), static_cast<int>(counts_.size()));
}

GridField ColumnAccumulator::sum() const {
  return {grid_, sums_};
}

GridField ColumnAccumulator::time_mean() const {
  GridField f{grid_, sums_};
  const double n = static_cast<double>(snapshots_);
  for (double& v : f.values) v = snapshots_ ? v / n : 0.0;
  return f;
}

GridField ColumnAccumulator::time_mean_count() const {
  GridField f{grid_, counts_};
  const double n = static_cast<double>(snapshots_);
  for (double& v : f.values) v = snapshots_ ? v / n : 0.0;
  return f;
}

GridField ColumnAccumulator::grain_mean() const {
  GridField f{grid_, sums_};
  for (std::size_t c = 0; c < f.values.size(); ++c)
    f.values[c] = counts_[c] > 0 ? sums_[c] / counts_[c] : std::nan("");
  return f;
}

void write_column_sum_csv(const std::filesystem::path& path, const GridField& sum,
                          const std::string& name) {
  const GridColumn column{name, sum.values};
  write_grid_csv(path, sum.grid, std::span<const GridColumn>(&column, 1));
}

} // namespace yuxi::analysis
