// Where a grain touches a shaped wall (a triangle mesh or a cylinder), and how the touches a
// grain has with one wall are reduced to its contacts.
//
// A wall offers, for one grain, its closest points: one per triangle of a mesh, one per
// surface patch of a cylinder, each on a face, an edge or a vertex. A sphere resting on a
// triangulated surface would otherwise see the same edge or vertex once per triangle that
// shares it, a face and the edge of its neighbour at once, and, once it sinks in, the edges of
// triangles further off. The rules (feature-based, in the manner of the region-based scheme of
// Kremmer & Favier, Int. J. Numer. Meth. Eng. 51 (2001) 1407; docs/walls.md section 2):
//   1. an edge point whose edge borders a triangle touched on its face is dropped, and each
//      edge counts once;
//   2. a vertex point whose vertex belongs to a triangle touched on its face or to an edge
//      touched is dropped, and each vertex counts once;
//   3. an edge or vertex point counts only where it is the closest point of every triangle
//      that holds its edge or vertex (the feature's own Voronoi region of the surface): on a
//      flat or convex part of a mesh the grain then sees what it sees on the plane, at any
//      overlap;
//   4. of touches whose normals differ by less than the merge angle, only the deepest counts:
//      coplanar triangles give one contact, and a sphere pressed into a finely faceted concave
//      surface one contact, not one per facet it overlaps.
// Two faces meeting at a concave corner (a groove) keep one contact each; a convex edge gives
// one contact whose normal turns continuously from one face's to the other's.
#pragma once

#include "core/vec3.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace yuxi {

struct WallTouch {
  Vec3 normal;               // unit, from the wall's surface point to the grain's centre
  double distance = 0;       // from the surface point to the centre; overlap = radius - distance
  Vec3 point;                // the wall's surface point [length]
  Vec3 velocity;             // the wall's velocity at that point [length/time]
  std::uint32_t element = 0; // triangle of a mesh, patch of a cylinder (side 0, caps 1 and 2)
};

// The contacts of one grain with one wall, deepest first.
struct WallTouches {
  static constexpr std::size_t capacity = 6;
  std::array<WallTouch, capacity> at;
  std::size_t n = 0;
  std::size_t dropped = 0; // touches beyond capacity (the shallowest), for diagnosis

  // Keeps t unless a touch already kept has a normal within the merge angle (cos_merge = its
  // cosine); touches must arrive deepest first.
  void keep_unless_merged(const WallTouch& t, double cos_merge) {
    for (std::size_t k = 0; k < n; ++k)
      if (dot(at[k].normal, t.normal) > cos_merge) return;
    if (n == capacity) {
      ++dropped;
      return;
    }
    at[n++] = t;
  }
};

// A candidate touch with the feature it lies on: kind 0 a face (a = triangle), 1 an edge
// (a < b: its vertices), 2 a vertex (a).
struct FeatureTouch {
  WallTouch touch;
  std::uint8_t kind = 0;
  std::uint32_t a = 0, b = 0;
};

// Applies rules 1-4 to the candidate touches of one grain with one mesh (each within reach:
// distance < radius). `corners(t)` gives the three vertex indices of triangle t;
// `feature_closest(c)` whether candidate c on an edge or a vertex passes rule 3. `order` is
// scratch space. In exact arithmetic the mesh's closest point passes every rule; should
// round-off drop every candidate, the deepest counts.
template <class Corners, class FeatureClosest>
void select_touches(const std::vector<FeatureTouch>& cand, double cos_merge, const Corners& corners,
                    const FeatureClosest& feature_closest, std::vector<std::uint32_t>& order,
                    WallTouches& out) {
  const std::size_t n_cand = cand.size();
  const auto touched_face_has = [&](std::uint32_t v) {
    for (std::size_t k = 0; k < n_cand; ++k)
      if (cand[k].kind == 0) {
        const auto c = corners(cand[k].a);
        if (c[0] == v || c[1] == v || c[2] == v) return true;
      }
    return false;
  };
  const auto touched_face_has_edge = [&](std::uint32_t va, std::uint32_t vb) {
    for (std::size_t k = 0; k < n_cand; ++k)
      if (cand[k].kind == 0) {
        const auto c = corners(cand[k].a);
        const bool has_a = c[0] == va || c[1] == va || c[2] == va;
        const bool has_b = c[0] == vb || c[1] == vb || c[2] == vb;
        if (has_a && has_b) return true;
      }
    return false;
  };
  const auto touched_edge_has = [&](std::uint32_t v) {
    for (std::size_t k = 0; k < n_cand; ++k)
      if (cand[k].kind == 1 && (cand[k].a == v || cand[k].b == v)) return true;
    return false;
  };
  // Rules 1 to 3 pick the candidates that count (a duplicate counts once).
  order.clear();
  std::size_t deepest = 0;
  for (std::size_t k = 0; k < n_cand; ++k) {
    const FeatureTouch& c = cand[k];
    if (c.touch.distance < cand[deepest].touch.distance) deepest = k;
    bool keep = true;
    if (c.kind == 1) keep = !touched_face_has_edge(c.a, c.b);
    if (c.kind == 2) keep = !touched_face_has(c.a) && !touched_edge_has(c.a);
    if (keep && c.kind != 0)
      for (const std::uint32_t j : order)
        if (cand[j].kind == c.kind && cand[j].a == c.a && cand[j].b == c.b) keep = false;
    if (keep && c.kind != 0) keep = feature_closest(c);
    if (keep) order.push_back(static_cast<std::uint32_t>(k));
  }
  if (order.empty() && n_cand > 0) order.push_back(static_cast<std::uint32_t>(deepest));
  // Rule 4, deepest first (ties: candidate order, which is ascending triangle index). An
  // insertion sort: a grain has a handful of touches, and it allocates nothing.
  for (std::size_t k = 1; k < order.size(); ++k) {
    const std::uint32_t moving = order[k];
    std::size_t j = k;
    for (; j > 0 && cand[order[j - 1]].touch.distance > cand[moving].touch.distance; --j)
      order[j] = order[j - 1];
    order[j] = moving;
  }
  out.n = 0;
  out.dropped = 0;
  for (const std::uint32_t k : order) out.keep_unless_merged(cand[k].touch, cos_merge);
}

} // namespace yuxi
