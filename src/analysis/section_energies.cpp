#include "analysis/section_energies.hpp"

#include "analysis/analysis_csv.hpp"

#include <array>
#include <stdexcept>

namespace yuxi::analysis {

SectionEnergies::SectionEnergies(const XYGrid& grid, std::span<const double> heights,
                                 double width) {
  if (heights.size() % 2 != 0)
    throw std::invalid_argument("section energies: heights come in pairs z0, z1");
  if (!(width >= 0.0))
    throw std::invalid_argument("section energies: the width must not be negative");
  for (std::size_t k = 0; k < heights.size(); k += 2) {
    if (!(heights[k] < heights[k + 1]))
      throw std::invalid_argument("section energies: each slab needs z0 < z1");
    Slab s;
    s.settings.kind = width > 0.0 ? CgKind::gaussian : CgKind::bins;
    s.settings.width = width;
    s.settings.cutoff = 3.0 * width;
    CgGrid& g = s.settings.grid;
    g.lo = {grid.lo().x, grid.lo().y, heights[k]};
    g.hi = {grid.hi().x, grid.hi().y, heights[k + 1]};
    g.n = {static_cast<int>(grid.nx()), static_cast<int>(grid.ny()), 1};
    g.averaged = {false, false, true};
    g.check();
    s.sums.assign(3 * g.size(), 0.0);
    slabs_.push_back(std::move(s));
  }
}

void SectionEnergies::add(std::span<const Vec3> x, std::span<const double> kinetic,
                          std::span<const double> elastic) {
  const std::vector<double> ones(x.size(), 1.0);
  const std::array<std::span<const double>, 3> quantities{ones, kinetic, elastic};
  for (Slab& s : slabs_) {
    const std::vector<double> d = coarse_grain_densities(x, quantities, s.settings);
    for (std::size_t k = 0; k < d.size(); ++k) s.sums[k] += d[k];
  }
  ++snapshots_;
}

void SectionEnergies::combine(const std::function<void(double*, int)>& sum_in_place) {
  for (Slab& s : slabs_) sum_in_place(s.sums.data(), static_cast<int>(s.sums.size()));
}

std::vector<double> SectionEnergies::means(std::size_t section) const {
  std::vector<double> out = slabs_.at(section).sums;
  if (snapshots_ > 0)
    for (double& v : out) v /= static_cast<double>(snapshots_);
  return out;
}

void SectionEnergies::write_csv(const std::filesystem::path& path) const {
  CsvWriter csv(path, {"section", "z0", "z1", "x", "y", "number_density", "kinetic_energy_density",
                       "elastic_energy_density"});
  for (std::size_t n = 0; n < slabs_.size(); ++n) {
    const CgGrid& g = slabs_[n].settings.grid;
    const std::vector<double> m = means(n);
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) {
        const std::size_t p = g.index(i, j, 0);
        csv.row({static_cast<double>(n), g.lo.z, g.hi.z, g.coordinate(0, i), g.coordinate(1, j),
                 m[3 * p], m[3 * p + 1], m[3 * p + 2]});
      }
  }
  csv.close();
}

} // namespace yuxi::analysis
