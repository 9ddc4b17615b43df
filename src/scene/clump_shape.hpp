// A clump: a rigid grain made of overlapping spheres (docs/clumps.md). Its shape is kept in its
// principal frame: the members' centres measured from the centre of mass along the principal
// axes of inertia, where the inertia tensor is diagonal.
#pragma once

#include "core/quaternion.hpp"
#include "core/random.hpp"
#include "core/vec3.hpp"
#include "scene/sphere_union.hpp"

#include <span>
#include <string>
#include <vector>

namespace yuxi {

struct ClumpShape {
  std::string name;
  std::vector<SphereMember> members; // in the principal frame
  double volume = 0;                 // of the union [length^3]
  // The principal moments of inertia over the density, ascending: I_k / rho [length^5].
  Vec3 inertia_per_density;
  // Where the shape was given: its frame turned from the principal one (v_given = frame v_body +
  // centre) and the centre of mass there.
  Quaternion frame;
  Vec3 centre;
  // The largest distance from the centre of mass to a member's surface [length].
  double bounding_radius = 0;

  // The same shape scaled by `factor` (> 0): every length times factor (the members and the
  // centre), the volume times factor^3, the moments times factor^5.
  ClumpShape scaled(double factor) const;
  // The largest distance of a member's centre from the anchor member's (clump_anchor below)
  // [length].
  double member_reach() const;
};

// The member whose place decides which MPI rank owns a clump: the one nearest the centre of
// mass (the first of equals), given the members' centres in the principal frame. Its own
// position, a particle's, decides as a sphere's does (sim/exchange.hpp), so a run resumed from
// the positions of its last list build makes the same owners again.
std::size_t clump_anchor(std::span<const Vec3> centres);
// The largest distance of a member's centre from the anchor's: how far outside its owner's
// sub-domain a member may stand [length].
double clump_reach(std::span<const Vec3> centres);

// An orientation drawn uniformly from all rotations (Shoemake, Graphics Gems III, 1992: a
// unit quaternion from three uniform numbers).
Quaternion random_orientation(Random& rng);

// The shape of `members`, given in any frame (radii > 0; throws std::invalid_argument naming
// the member that is not). A member inside another (a member given twice among them) is left
// out: it adds nothing to the union, and would stiffen the clump's contacts.
ClumpShape make_clump_shape(std::string name, std::span<const SphereMember> members);

} // namespace yuxi
