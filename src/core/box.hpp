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
  // p (wrapped) and its periodic images that lie within `reach` of the box: what a ball of
  // radius `reach` about p meets across the periodic faces (at most 8, p first).
  struct Images {
    std::array<Vec3, 8> at;
    int n = 0;
    const Vec3* begin() const { return at.data(); }
    const Vec3* end() const { return at.data() + n; }
  };
  Images images_within(const Vec3& p, double reach) const;
};

} // namespace yuxi
