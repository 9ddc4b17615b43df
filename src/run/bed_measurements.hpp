// The [[measure]] tables of a scene (scene/measure_spec.hpp), evaluated on the energy interval
// into measurements.csv: one row per interval, `step,time` and each measure's columns.
// Every rank measures its own grains; sums and column heights are reduced over the ranks (no
// particle is gathered).
#pragma once

#include "scene/measure_spec.hpp"
#include "sim/simulation.hpp"

#include <string>
#include <vector>

namespace yuxi {

class BedMeasurements {
public:
  // `largest_radius`: of any grain the run may hold (the default column width is its 4 radii).
  // Throws std::invalid_argument for a wall_force measure that names no wall of the simulation.
  BedMeasurements(std::vector<MeasureSpec> specs, const Simulation& sim, double largest_radius);

  bool empty() const { return specs_.empty(); }
  // "step,time,<columns>".
  std::string header() const;
  // The columns' values at the simulation's current state, in header order. Collective.
  std::vector<double> values(const Simulation& sim) const;

private:
  struct WallRef {
    bool plane = false;
    std::size_t index = 0;
  };
  std::vector<MeasureSpec> specs_;
  std::vector<WallRef> walls_; // per spec (wall_force only)
  double default_bin_;
};

} // namespace yuxi
