// The simulation box: an axis-aligned region with a boundary type on each axis.
#pragma once

#include "core/vec3.hpp"

#include <array>
#include <string_view>

namespace yuxi {

// What happens at the two faces of one axis.
//  periodic: a grain leaving one face re-enters through the other;
//  wall:     a flat frictional wall (grain-wall material) stands at each face;
//  open:     nothing stops grains; one that leaves the box is handled by the escape policy.
enum class Boundary { periodic, wall, open };

std::string_view to_string(Boundary b);

struct Box {
  Vec3 lo, hi;
  std::array<Boundary, 3> boundary{Boundary::open, Boundary::open, Boundary::open};

  double length(int axis) const { return hi[axis] - lo[axis]; }
  bool periodic(int axis) const { return boundary[axis] == Boundary::periodic; }
  bool contains(const Vec3& p) const;
  // Maps a position into [lo, hi) along periodic axes; other axes unchanged.
  Vec3 wrap(Vec3 p) const;
  // Shortest separation vector a - b, using periodic images along periodic axes.
  Vec3 minimum_image(const Vec3& a, const Vec3& b) const;
};

} // namespace yuxi
