// The volume, first and second moments of a union of overlapping spheres (a clump's members;
// docs/clumps.md, section 1): what its mass, centre of mass and inertia tensor follow from, with
// each overlap counted once.
//
// Method: the solid is sliced along z. A slice is a union of discs; its area and its first and
// second area moments are exact line integrals (Green's theorem) along the arcs of its boundary,
// the parts of each circle that no other disc covers. Along z these are smooth between the
// heights where a member begins or ends, where two members' discs begin or stop to cross (the
// top and bottom of the circle where two spheres meet) and where three spheres' surfaces meet;
// between consecutive such heights the integral over z is Gauss-Legendre quadrature after the
// substitution z = a + (b - a) sin^2(pi u / 2), which makes the square-root behaviour at the
// ends smooth. Accuracy (tests/unit/test_clump_shape.cpp): 1e-13 relative against the closed
// forms of one sphere, two overlapping ones and a chain of three, and the same moments, turned,
// for a random clump in any orientation.
#pragma once

#include "core/vec3.hpp"

#include <array>
#include <span>

namespace yuxi {

struct SphereMember {
  Vec3 centre;
  double radius = 0;
};

// Integrals over the union's volume: volume = the integral of 1, first = of r, second[a][b] = of
// r_a r_b (about the origin of the members' frame).
struct VolumeMoments {
  double volume = 0;
  Vec3 first;
  std::array<std::array<double, 3>, 3> second{};
};

// The moments of the union of `members` (radii > 0; members inside others and repeated members
// count once).
VolumeMoments sphere_union_moments(std::span<const SphereMember> members);

} // namespace yuxi
