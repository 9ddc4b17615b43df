// Keeping a tangential spring in the tangent plane as the contact normal turns.
#pragma once

#include "core/vec3.hpp"

namespace yuxi {

// Projects s onto the plane normal to n and restores its length, so that turning the frame
// neither creates nor destroys spring energy (LAMMPS gran/hooke/history and Luding 2008 do the
// projection; the rescale keeps the stored energy exact).
inline Vec3 rotate_into_tangent_plane(const Vec3& s, const Vec3& n) {
  const double len2 = norm2(s);
  if (len2 == 0.0) return s;
  Vec3 p = s - dot(s, n) * n;
  const double p2 = norm2(p);
  if (p2 == 0.0) return Vec3{};
  return p * std::sqrt(len2 / p2);
}

} // namespace yuxi
