// A triangle mesh: vertices shared between the triangles that meet there, so that edges and
// vertices have an identity (the contact rules of wall_touch.hpp rely on it).
#pragma once

#include "core/vec3.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace yuxi {

struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles; // vertex indices

  // Joins the corners of a triangle soup (as an STL file lists them) that have exactly the same
  // coordinates into one vertex; triangles keep their order.
  static TriangleMesh weld(const std::vector<std::array<Vec3, 3>>& soup);

  // Scales by `scale` about the origin, then turns by `degrees` about the unit `axis` through
  // the origin, then shifts by `shift`.
  void transform(double scale, const Vec3& axis, double degrees, const Vec3& shift);

  // The listed triangles (ascending indices), in that order, with the vertices they use, in
  // the order of their indices here: a part of the mesh whose edges and vertices keep their
  // identity, and whose triangles and vertices keep their relative order.
  TriangleMesh subset(std::span<const std::uint32_t> kept) const;

  std::size_t n_triangles() const { return triangles.size(); }
  // The box of triangle t with its corners at `at` (the vertices, or where they were placed).
  std::pair<Vec3, Vec3> box_of(std::size_t t, const std::vector<Vec3>& at) const {
    const auto& tri = triangles[t];
    Vec3 lo = at[tri[0]], hi = lo;
    for (int k = 1; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], at[tri[k]][a]);
        hi[a] = std::max(hi[a], at[tri[k]][a]);
      }
    return {lo, hi};
  }
  // Every vertex's coordinates finite (a transform cannot make them otherwise unless huge).
  bool finite() const;
  // Edges shared by more than two triangles (a non-manifold mesh works, but rule 1 of
  // wall_touch.hpp then treats the edge as bordering all of them).
  std::size_t non_manifold_edges() const;
};

} // namespace yuxi
