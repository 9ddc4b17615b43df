// Per-grain quantities gathered into the columns of an x-y grid.
//
// column_sum: the sum over z of a per-grain quantity in each column, e.g. the vertically summed
// elastic energy of Li & Cai (2008) Fig. 8 (energy in m sigma^2 / tau^2 per column).
// (Fig. 9's horizontal sections are coarse-grained: section_energies.hpp.)
//
// CSV of a column sum (write_column_sum_csv), e.g. analysis/elastic_map_t10.25.csv:
//   x,y,<name>          one row per column, x fastest (numpy: reshape(ny, nx)); <name> e.g.
//                       "elastic"; 0 in empty columns.
#pragma once

#include "analysis/xy_grid.hpp"
#include "core/vec3.hpp"

#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace yuxi::analysis {

// Sum of values[k] over the grains k whose centre positions[k] lies in each column (any z);
// 0 for an empty column. Throws std::invalid_argument if the spans differ in size.
GridField column_sum(const XYGrid& grid, std::span<const Vec3> positions,
                     std::span<const double> values);

void write_column_sum_csv(const std::filesystem::path& path, const GridField& sum,
                          const std::string& name);

} // namespace yuxi::analysis
