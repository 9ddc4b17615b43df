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

void write_sections_csv(const std::filesystem::path& path,
                        std::span<const EnergySection> sections) {
  for (const auto& s : sections) {
    const auto& e = *s.elastic;
    const auto& k = *s.kinetic;
    if (e.grid().nx() != k.grid().nx() || e.grid().ny() != k.grid().ny() ||
        !(e.grid().lo() == k.grid().lo()) || !(e.grid().hi() == k.grid().hi()) ||
        e.z0() != k.z0() || e.z1() != k.z1() || e.snapshots() != k.snapshots())
      throw std::invalid_argument("write_sections_csv: elastic and kinetic accumulators differ");
    if (e.grid().size() != sections[0].elastic->grid().size())
      throw std::invalid_argument("write_sections_csv: sections on grids of different sizes");
  }
  CsvWriter csv(path, {"section", "z0", "z1", "x", "y", "grains", "elastic", "kinetic"});
  for (std::size_t n = 0; n < sections.size(); ++n) {
    const auto& e = *sections[n].elastic;
    const XYGrid& g = e.grid();
    const GridField grains = e.time_mean_count();
    const GridField elastic = e.time_mean();
    const GridField kinetic = sections[n].kinetic->time_mean();
    for (std::size_t j = 0; j < g.ny(); ++j)
      for (std::size_t i = 0; i < g.nx(); ++i) {
        const std::size_t c = g.index(i, j);
        csv.row({static_cast<double>(n), e.z0(), e.z1(), g.x_center(i), g.y_center(j),
                 grains.values[c], elastic.values[c], kinetic.values[c]});
      }
  }
  csv.close();
}

} // namespace yuxi::analysis
