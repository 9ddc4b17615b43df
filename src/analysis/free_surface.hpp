// The free surface of a granular bed (Li & Cai 2008, Figs. 5 and 6): over each column of an x-y
// grid, the height of the highest grain top, max(z + r) over the grains whose centres lie in
// the column; NaN for a column that holds no grain. Lengths in the scene's units (sigma).
//
// CSV (write_surface_csv), e.g. analysis/surface_t10.25.csv:
//   x,y,height     one row per column, x fastest (numpy: height.reshape(ny, nx)); x, y the
//                  column centre; height NaN ("nan") for an empty column.
#pragma once

#include "analysis/xy_grid.hpp"
#include "core/vec3.hpp"

#include <filesystem>
#include <span>

namespace yuxi::analysis {

// Pass grains only (wall particles would count as surface). positions[k] is the centre and
// radii[k] the radius of grain k. Grains outside the grid are ignored. Throws
// std::invalid_argument if the spans differ in size.
GridField free_surface(const XYGrid& grid, std::span<const Vec3> positions,
                       std::span<const double> radii);

void write_surface_csv(const std::filesystem::path& path, const GridField& surface);

} // namespace yuxi::analysis
