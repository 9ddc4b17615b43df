// A frictional, polydisperse pile of 108 grains dropped onto a still egg-crate mesh, where
// grains touch faces, convex and concave edges and vertices, several triangles at once, and hand
// their contacts from one triangle to the next.
#pragma once

#include "core/random.hpp"
#include "test_support.hpp"

#include <array>
#include <cmath>
#include <vector>

namespace yuxi::test {

// A 10 x 10 floor of squares, each cut into two triangles, its vertices at
// z = -3 + 0.35 sin(1.3 x) sin(1.1 y).
inline MeshWall egg_crate() {
  const auto z = [](double x, double y) {
    return -3.0 + 0.35 * std::sin(1.3 * x) * std::sin(1.1 * y);
  };
  std::vector<std::array<Vec3, 3>> soup;
  const double edge = 0.8;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const double x0 = -4 + i * edge, y0 = -4 + j * edge, x1 = x0 + edge, y1 = y0 + edge;
      const Vec3 a{x0, y0, z(x0, y0)}, b{x1, y0, z(x1, y0)}, c{x1, y1, z(x1, y1)},
          d{x0, y1, z(x0, y1)};
      soup.push_back({a, b, c});
      soup.push_back({a, c, d});
    }
  MeshWall w;
  w.name = "floor";
  w.mesh = TriangleMesh::weld(soup);
  w.material = 1;
  return w;
}

// `unused_convention`: a third material, in no contact, whose pairs cap friction differently,
// so that the law cannot be batched (LinearBatch::prepare) and every contact goes one by one.
inline Simulation pile_on_mesh(double near_fraction, bool unused_convention) {
  Random rng(5);
  auto cfg = open_box(4.0, {0.1, 0.0, -1.0}, 5e-4);
  cfg.box.boundary = {Boundary::wall, Boundary::wall, Boundary::open};
  cfg.box.hi.z = 8.0;
  cfg.skin = 0.3;
  cfg.near_fraction = near_fraction;
  std::vector<ParticleSpec> specs;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 3; ++k)
        specs.push_back(sphere({-3.0 + 1.2 * i, -3.0 + 1.2 * j, -1.8 + 1.1 * k},
                               rng.uniform(0.35, 0.5), 0.5,
                               {rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 0},
                               {rng.uniform(-1, 1), rng.uniform(-1, 1), 0}));
  const Coeffs c{5e3, 1.5e3, 50.0, 20.0, 0.6, 0.4};
  ContactLaw<LinearSpringDashpot> law{PairTable<Coeffs>(3)};
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = a; b < 3; ++b) law.coeffs.set(a, b, c);
  if (unused_convention) {
    Coeffs other = c;
    other.friction_cap = CapOn::total;
    law.coeffs.set(2, 2, other);
  }
  return Simulation(cfg, store_of(specs), {}, {}, law, Comm::self(), {egg_crate()});
}

} // namespace yuxi::test
