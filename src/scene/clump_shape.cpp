// A clump's mass properties and principal frame (clump_shape.hpp).
#include "scene/clump_shape.hpp"

#include "core/symmetric_eigen3.hpp"
#include "core/units.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>
#include <vector>

namespace yuxi {

std::size_t clump_anchor(std::span<const Vec3> centres) {
  std::size_t anchor = 0;
  for (std::size_t k = 1; k < centres.size(); ++k)
    if (norm2(centres[k]) < norm2(centres[anchor])) anchor = k;
  return anchor;
}

double clump_reach(std::span<const Vec3> centres) {
  if (centres.empty()) return 0.0;
  const Vec3 anchor = centres[clump_anchor(centres)];
  double r = 0.0;
  for (const Vec3& c : centres) r = std::max(r, norm(c - anchor));
  return r;
}

double ClumpShape::member_reach() const {
  std::vector<Vec3> centres;
  for (const SphereMember& m : members) centres.push_back(m.centre);
  return clump_reach(centres);
}

Quaternion random_orientation(Random& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return {a * std::sin(2.0 * pi * u2), a * std::cos(2.0 * pi * u2), b * std::sin(2.0 * pi * u3),
          b * std::cos(2.0 * pi * u3)};
}

namespace {

// The members that no other member encloses (the first of a member given twice): an enclosed
// member adds nothing to the union, and in a contact it would push again where the member
// that holds it already pushes, stiffening the clump there.
std::vector<SphereMember> outside_one_another(std::span<const SphereMember> members) {
  const auto encloses = [&](std::size_t i, std::size_t j) {
    return norm(members[i].centre - members[j].centre) + members[j].radius <= members[i].radius;
  };
  std::vector<SphereMember> kept;
  for (std::size_t j = 0; j < members.size(); ++j) {
    bool enclosed = false;
    for (std::size_t i = 0; i < members.size() && !enclosed; ++i)
      enclosed = i != j && encloses(i, j) && (!encloses(j, i) || i < j);
    if (!enclosed) kept.push_back(members[j]);
  }
  return kept;
}

} // namespace

ClumpShape make_clump_shape(std::string name, std::span<const SphereMember> given) {
  if (given.empty()) throw std::invalid_argument(fmt::format("shape \"{}\": no members", name));
  for (std::size_t k = 0; k < given.size(); ++k) {
    const SphereMember& m = given[k];
    if (!(m.radius > 0) || !std::isfinite(m.radius) || !is_finite(m.centre))
      throw std::invalid_argument(fmt::format(
          "shape \"{}\", member {}: radius {} at ({}, {}, {}); a member needs a finite radius > "
          "0 and a finite centre",
          name, k + 1, m.radius, m.centre.x, m.centre.y, m.centre.z));
    // (the size check below squares lengths: beyond 1e50 they would overflow to inf first)
    const double far =
        std::max({std::abs(m.centre.x), std::abs(m.centre.y), std::abs(m.centre.z), m.radius});
    if (far > 1e50)
      throw std::invalid_argument(fmt::format(
          "shape \"{}\", member {}: radius {} at ({}, {}, {}) lies beyond 1e50 in the scene's "
          "units",
          name, k + 1, m.radius, m.centre.x, m.centre.y, m.centre.z));
  }
  const std::vector<SphereMember> kept = outside_one_another(given);
  const std::span<const SphereMember> members = kept;
  // The moments are taken about the members' mean centre, so that a clump given far from its
  // frame's origin loses no digits to the parallel-axis terms.
  Vec3 origin;
  for (const SphereMember& m : members) origin += m.centre / static_cast<double>(members.size());
  std::vector<SphereMember> near;
  double extent = 0;
  for (const SphereMember& m : members) {
    near.push_back({m.centre - origin, m.radius});
    extent = std::max(extent, norm(m.centre - origin) + m.radius);
  }
  // Its moments go as the fifth power of its size: within these bounds they stay normal doubles.
  if (!(extent >= 1e-50 && extent <= 1e50))
    throw std::invalid_argument(fmt::format(
        "shape \"{}\": its size {} lies outside 1e-50 to 1e50 in the scene's units", name, extent));
  for (std::size_t k = 0; k < members.size(); ++k)
    if (members[k].radius < 1e-6 * extent)
      throw std::invalid_argument(
          fmt::format("shape \"{}\", member {}: radius {} is below 1e-6 of the clump's size {}",
                      name, k + 1, members[k].radius, extent));
  const VolumeMoments v = sphere_union_moments(near);
  ClumpShape s;
  s.name = std::move(name);
  s.volume = v.volume;
  const Vec3 centre = v.first / v.volume; // from the origin
  // The inertia tensor over the density about the centre of mass: I = tr(S) 1 - S with S the
  // central second moments, S_ab = integral of r_a r_b - V c_a c_b.
  std::array<std::array<double, 3>, 3> central{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) central[a][b] = v.second[a][b] - v.volume * centre[a] * centre[b];
  const double trace = central[0][0] + central[1][1] + central[2][2];
  std::array<std::array<double, 3>, 3> inertia{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) inertia[a][b] = (a == b ? trace : 0.0) - central[a][b];
  const SymmetricEigen3 e = symmetric_eigen3(inertia);
  s.inertia_per_density = {e.values[0], e.values[1], e.values[2]};
  // The rotation whose columns are the principal axes turns the principal frame into the given.
  double m[3][3];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) m[r][c] = e.axes[c][r];
  s.frame = from_rotation_matrix(m);
  s.centre = origin + centre;
  for (const SphereMember& member : members) {
    const Vec3 body = to_body(s.frame, member.centre - s.centre);
    s.members.push_back({body, member.radius});
    s.bounding_radius = std::max(s.bounding_radius, norm(body) + member.radius);
  }
  return s;
}

ClumpShape ClumpShape::scaled(double factor) const {
  ClumpShape s = *this;
  for (SphereMember& m : s.members) {
    m.centre *= factor;
    m.radius *= factor;
  }
  s.volume *= factor * factor * factor;
  s.inertia_per_density *= std::pow(factor, 5);
  s.bounding_radius *= factor;
  s.centre *= factor;
  return s;
}

} // namespace yuxi
