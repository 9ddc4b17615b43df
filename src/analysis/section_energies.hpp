// Fig. 9 of Li & Cai (2008) by coarse-graining (docs/coarse-graining.md): the grains' number,
// kinetic and elastic energy densities in horizontal slabs z0 <= z <= z1, resolved in x and y on
// the analysis grid and averaged over z within each slab (a grain whose centre lies outside the
// slab does not count; one exactly on a face shared by two slabs counts in both), then averaged
// over the snapshots of the first excitation period. With bins (width 0) a cell's value is the
// total of its grains over its volume, the paper's cells; with a Gaussian of width w (cut off at 3
// w), the smooth field at the cells' centres. Every grain's energy stands at its centre: its
// kinetic energy, and half of each of its contacts' elastic energy (the per-grain energies of Fig.
// 10).
//
// CSV (write_csv), analysis/period_sections.csv:
//   section,z0,z1,x,y,number_density,kinetic_energy_density,elastic_energy_density
//   section = 0, 1, ... (the rows of a section x fastest; numpy: reshape(ny, nx)); time means
//   per unit volume (1/sigma^3 and m sigma^2/tau^2 per sigma^3 in reduced units).
#pragma once

#include "analysis/coarse_grain.hpp"
#include "analysis/xy_grid.hpp"
#include "core/vec3.hpp"

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <vector>

namespace yuxi::analysis {

class SectionEnergies {
public:
  // One slab for each pair z0, z1 of `heights` on the columns of `grid`. Throws
  // std::invalid_argument for an odd count, a slab with z1 <= z0, or a negative width.
  SectionEnergies(const XYGrid& grid, std::span<const double> heights, double width);

  bool empty() const { return slabs_.empty(); }
  std::size_t snapshots() const { return snapshots_; }
  // One snapshot: the grains' centres and their kinetic and elastic energies.
  void add(std::span<const Vec3> x, std::span<const double> kinetic,
           std::span<const double> elastic);
  // Adds up the sums of several processes (each saw its own grains at the same snapshots):
  // `sum_in_place(values, n)` must sum n doubles over them, in place.
  void combine(const std::function<void(double*, int)>& sum_in_place);
  // A section's time means at its points (x fastest): number, kinetic and elastic energy
  // densities, three values a point.
  std::vector<double> means(std::size_t section) const;
  void write_csv(const std::filesystem::path& path) const;

private:
  struct Slab {
    CgSettings settings;
    std::vector<double> sums; // over the snapshots, three a point
  };
  std::vector<Slab> slabs_;
  std::size_t snapshots_ = 0;
};

} // namespace yuxi::analysis
