// Triangulated surfaces for the tests of mesh walls: a grid of cells over (u, v) in [0, 1]^2,
// mapped onto a surface, its inner vertices moved at random and each cell cut along a random
// diagonal, so that edges and vertices fall anywhere under a grain.
#pragma once

#include "core/random.hpp"
#include "scene/mesh_wall.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace yuxi::test {

using TriangleSoup = std::vector<std::array<Vec3, 3>>;

// `place(u, v)` maps the parameters onto the surface. The vertices on the grid's border stay
// where the grid puts them, at u = i / nu and v = j / nv exactly: two surfaces whose `place`
// gives the same bits there weld into one mesh along that border. The inner vertices move by
// up to `jitter` of a cell in u and in v, but those on the grid lines u = i / nu listed in
// `straight_u` (a ridge, a crease) move along v only. Below 1/6 of a cell no triangle turns
// over: the triangles tile the surface without overlapping.
template <class Place>
TriangleSoup random_surface(int nu, int nv, std::uint64_t seed, const Place& place,
                            const std::vector<int>& straight_u = {}, double jitter = 0.15) {
  Random rng(seed);
  std::vector<Vec3> at;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      double u = double(i) / nu, v = double(j) / nv;
      if (i > 0 && j > 0 && i < nu && j < nv) {
        const double du = rng.uniform(-jitter, jitter) / nu, dv = rng.uniform(-jitter, jitter) / nv;
        if (std::find(straight_u.begin(), straight_u.end(), i) == straight_u.end()) u += du;
        v += dv;
      }
      at.push_back(place(u, v));
    }
  const auto vertex = [&](int i, int j) { return at[static_cast<std::size_t>(j * (nu + 1) + i)]; };
  TriangleSoup soup;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const Vec3 a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                 d = vertex(i, j + 1);
      if (rng.uniform() < 0.5) {
        soup.push_back({{a, b, c}});
        soup.push_back({{a, c, d}});
      } else {
        soup.push_back({{a, b, d}});
        soup.push_back({{b, c, d}});
      }
    }
  return soup;
}

// A disc cut into a fan about its centre: `spokes` triangles meet at the centre, and `rings`
// rings of as many vertices each, at angles 2 pi (i + s) / spokes (i counted from 0, s at
// random in [-0.15, 0.15]), are joined by quadrilaterals cut along a random diagonal.
// `place(rho, phi)` maps a radius (0 to 1) and an angle onto the surface. The outer ring lies
// at radius 1 and each ring inside at c times the one outside it, give or take 5 %, with
// c = 0.8 cos(1.3 pi / spokes): within the chords of the ring outside, so that no triangle
// turns over.
template <class Place>
TriangleSoup random_fan(int spokes, int rings, std::uint64_t seed, const Place& place) {
  Random rng(seed);
  constexpr double pi = 3.141592653589793;
  const double ratio = 0.8 * std::cos(1.3 * pi / spokes);
  std::vector<std::vector<Vec3>> ring(static_cast<std::size_t>(rings));
  for (int k = 0; k < rings; ++k)
    for (int i = 0; i < spokes; ++i) {
      double rho = 1.0;
      for (int inside = k + 1; inside < rings; ++inside)
        rho *= ratio * (1 + rng.uniform(-0.05, 0.05));
      ring[k].push_back(place(rho, 2 * pi * (i + rng.uniform(-0.15, 0.15)) / spokes));
    }
  const Vec3 centre = place(0.0, 0.0);
  TriangleSoup soup;
  for (int i = 0; i < spokes; ++i) {
    const std::size_t a = static_cast<std::size_t>(i),
                      b = static_cast<std::size_t>((i + 1) % spokes);
    soup.push_back({{centre, ring[0][a], ring[0][b]}});
    for (int k = 0; k + 1 < rings; ++k) {
      const auto& in = ring[k];
      const auto& out = ring[k + 1];
      if (rng.uniform() < 0.5) {
        soup.push_back({{in[a], out[a], out[b]}});
        soup.push_back({{in[a], out[b], in[b]}});
      } else {
        soup.push_back({{in[a], out[a], in[b]}});
        soup.push_back({{in[b], out[a], out[b]}});
      }
    }
  }
  return soup;
}

// A mesh wall of the given triangles, placed at t = 0.
inline MeshWall mesh_wall_of(const TriangleSoup& soup, const std::string& name = "mesh") {
  MeshWall w;
  w.name = name;
  w.mesh = TriangleMesh::weld(soup);
  w.place(0.0);
  return w;
}

// The contacts of a sphere (centre c, radius r) with every triangle of a placed mesh wall.
inline WallTouches touches_of(const MeshWall& w, const Vec3& c, double r) {
  std::vector<std::uint32_t> all(w.mesh.n_triangles());
  for (std::uint32_t t = 0; t < all.size(); ++t) all[t] = t;
  std::vector<FeatureTouch> scratch;
  std::vector<std::uint32_t> order;
  WallTouches out;
  w.touches(c, r, all, scratch, order, out);
  return out;
}

} // namespace yuxi::test
