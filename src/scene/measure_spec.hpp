// What a [[measure]] table asks a run to write into measurements.csv on every energy interval
// (docs/scene-format.md, "Measuring a bed"), so that a benchmark is a scene plus a short script:
//   mass, grains          the mass, or the number, of grains whose centres lie in the region
//                         (a clump is one grain, at its centre of mass, of its whole mass)
//   kinetic_per_grain     (sum m v^2/2 + J w^2/2) / N over those grains: "at rest" when small
//                         (a clump's M V^2/2 plus its rotational energy)
//   surface_height        the median, over the columns of width `bin` on the x-y plane that hold
//                         a grain, of the highest grain top max(z + r) (heights along z)
//   angle                 the bed's angle [degrees]: a straight line fitted by least squares to
//                         the column tops h against s, the column's position along `direction`
//                         (s = (c - point) . direction) or its distance from the vertical axis
//                         through `point` (a heap about an axis), for s in [from, to];
//                         angle = atan |dh/ds|, with the fit's R^2 in its own column
//   wall_force            the force of the grains on a named wall ([[plane]], [[mesh]],
//                         [[cylinder]]): three columns, x, y, z
// The region is the whole domain where none is given.
#pragma once

#include "scene/region.hpp"

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace yuxi {

struct MeasureSpec {
  enum class Quantity { mass, grains, kinetic_per_grain, surface_height, angle, wall_force };
  std::string name;
  Quantity quantity = Quantity::mass;
  std::optional<Region> region;
  // surface_height, angle
  double bin = 0; // column width [length]
  // angle
  bool about_axis = false; // s: distance from the vertical axis through `point`
  Vec3 point;
  Vec3 direction{1, 0, 0}; // horizontal, unit
  double from = -std::numeric_limits<double>::infinity();
  double to = std::numeric_limits<double>::infinity();
  // wall_force
  std::string wall;

  // The names of its columns in measurements.csv.
  std::vector<std::string> columns() const {
    switch (quantity) {
    case Quantity::angle:
      return {name, name + "_r2"};
    case Quantity::wall_force:
      return {name + "_x", name + "_y", name + "_z"};
    default:
      return {name};
    }
  }
};

} // namespace yuxi
