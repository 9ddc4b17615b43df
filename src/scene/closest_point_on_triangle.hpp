// The point of a triangle closest to a given point, and which feature of the triangle it lies
// on: the face, an edge or a vertex. The region test of Ericson, Real-Time Collision Detection
// (2005), section 5.1.5: the point's projections onto the edges decide its Voronoi region
// of the triangle, with no square root and no division outside the region found.
#pragma once

#include "core/vec3.hpp"

#include <cstdint>

namespace yuxi {

// The feature a closest point lies on. Edges are named by their vertices: edge_ab joins
// vertices a and b of the triangle (a, b, c).
enum class TriangleFeature : std::uint8_t {
  face,
  edge_ab,
  edge_bc,
  edge_ca,
  vertex_a,
  vertex_b,
  vertex_c
};

struct TrianglePoint {
  Vec3 point;
  double weight[3]; // barycentric weights of a, b, c (point = sum weight[k] vertex[k])
  TriangleFeature feature;
};

// Without `face_point`, a point on the face is returned as the feature alone (its point and
// weights unset): a caller that has the triangle's plane needs no more.
template <bool face_point = true>
inline TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                               const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, {1, 0, 0}, TriangleFeature::vertex_a};
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, {0, 1, 0}, TriangleFeature::vertex_b};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {a + v * ab, {1 - v, v, 0}, TriangleFeature::edge_ab};
  }
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, {0, 0, 1}, TriangleFeature::vertex_c};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {a + w * ac, {1 - w, 0, w}, TriangleFeature::edge_ca};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + w * (c - b), {0, 1 - w, w}, TriangleFeature::edge_bc};
  }
  if constexpr (!face_point) return {Vec3{}, {0, 0, 0}, TriangleFeature::face};
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {a + v * ab + w * ac, {1 - v - w, v, w}, TriangleFeature::face};
}

} // namespace yuxi
