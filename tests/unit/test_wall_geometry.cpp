// The geometry of shaped walls: closest points on triangles, the rules that turn a grain's
// touches with a mesh into contacts (scene/wall_touch.hpp), cylinders, rigid motions.
#include "core/random.hpp"
#include "mesh_surfaces.hpp"
#include "scene/closest_point_on_triangle.hpp"
#include "scene/cylinder_wall.hpp"
#include "scene/mesh_wall.hpp"
#include "scene/rigid_motion.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace yuxi {
namespace {

MeshWall mesh_of(const test::TriangleSoup& soup) {
  return test::mesh_wall_of(soup);
}
using test::touches_of;

TEST(ClosestPointOnTriangle, IsNoFartherThanAnyPointOfTheTriangle) {
  Random rng(11);
  const auto any = [&] { return Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}; };
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 a = any(), b = any(), c = any(), p = 2.0 * any();
    const TrianglePoint q = closest_point_on_triangle(p, a, b, c);
    // the point is the triangle's own, with its weights
    const Vec3 from_weights = q.weight[0] * a + q.weight[1] * b + q.weight[2] * c;
    EXPECT_LT(norm(from_weights - q.point), 1e-12);
    for (double w : q.weight) EXPECT_GE(w, -1e-12);
    EXPECT_NEAR(q.weight[0] + q.weight[1] + q.weight[2], 1.0, 1e-12);
    // and no point of a dense barycentric grid is closer
    const double d = norm(p - q.point);
    constexpr int n = 40;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const Vec3 s = a + (double(i) / n) * (b - a) + (double(j) / n) * (c - a);
        ASSERT_LE(d, norm(p - s) + 1e-12) << "trial " << trial;
      }
    // the feature matches the weights
    const int zero = (q.weight[0] == 0) + (q.weight[1] == 0) + (q.weight[2] == 0);
    if (q.feature == TriangleFeature::face) {
      EXPECT_EQ(zero, 0);
    }
    if (q.feature >= TriangleFeature::vertex_a) {
      EXPECT_EQ(zero, 2);
    }
  }
}

// The quick look of MeshWall::touches (docs/walls.md section 1) settles most triangles by their
// barycentric weights, with a slack for round-off: its answer must be the region test's, to the
// bit. Each grain here is placed where the two could part: its foot near an edge or a corner
// (within 1e-6 to 1e-15 of the triangle's edge length, on either side), with its surface near the
// closest point (within as little), on well-shaped triangles, slivers and large triangles
// under small grains.
TEST(MeshTouches, TheQuickLookAgreesWithTheRegionTestToTheBit) {
  Random rng(11);
  const auto any = [&] { return Vec3{rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)}; };
  int touched = 0, missed = 0, faces = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double size = trial % 3 == 0 ? 100.0 : 1.0;
    Vec3 a = size * any(), b = size * any(), c = size * any();
    if (trial % 5 == 0) c = a + (b - a) * rng.uniform(0.1, 0.9) + 1e-5 * size * any(); // sliver
    if (norm2(cross(b - a, c - a)) == 0.0) continue;
    const MeshWall w = mesh_of({{{a, b, c}}});
    if (w.mesh.n_triangles() != 1) continue;
    const auto& tri = w.mesh.triangles[0];
    const Vec3 pa = w.mesh.vertices[tri[0]], pb = w.mesh.vertices[tri[1]],
               pc = w.mesh.vertices[tri[2]];
    // a foot on an edge or at a corner, pushed in or out by a tiny step, and a grain above it
    const double t = rng.uniform() < 0.3 ? 0.0 : rng.uniform();
    const Vec3 ends[3][2] = {{pa, pb}, {pb, pc}, {pc, pa}};
    const int e = static_cast<int>(rng.uniform() * 3) % 3;
    const Vec3 on_edge = ends[e][0] + t * (ends[e][1] - ends[e][0]);
    const Vec3 centroid = (pa + pb + pc) * (1.0 / 3.0);
    const double step = std::pow(10.0, -rng.uniform(6, 15)) * (rng.uniform() < 0.5 ? 1 : -1);
    const Vec3 foot = on_edge + step * (centroid - on_edge);
    const Vec3 n = w.placed[0].normal;
    const double height = rng.uniform(0.0, 0.5) * (trial % 3 == 0 ? 0.02 : 1.0) * size;
    const Vec3 centre = foot + height * n + 1e-3 * height * any();
    const TrianglePoint q = closest_point_on_triangle(centre, pa, pb, pc);
    const double above = dot(n, centre - pa);
    const double reach =
        q.feature == TriangleFeature::face ? std::abs(above) : norm(centre - q.point);
    const double r =
        reach * (1.0 + std::pow(10.0, -rng.uniform(8, 15)) * (rng.uniform() < 0.5 ? 1 : -1));
    // what the region test alone gives (MeshWall::touches before its quick look)
    bool expect = above * above < r * r;
    double distance = std::abs(above);
    if (expect && q.feature != TriangleFeature::face) {
      const double d2 = norm2(centre - q.point);
      expect = d2 < r * r;
      distance = std::sqrt(d2);
    }
    const WallTouches got = touches_of(w, centre, r);
    ASSERT_EQ(got.n, expect ? 1u : 0u) << "trial " << trial;
    if (!expect) {
      ++missed;
      continue;
    }
    ++touched;
    faces += q.feature == TriangleFeature::face;
    EXPECT_EQ(got.at[0].distance, distance) << "trial " << trial;
  }
  // (the grains lie on both sides of the boundaries, on faces and beyond edges)
  EXPECT_GT(touched, 500);
  EXPECT_GT(missed, 500);
  EXPECT_GT(faces, 200);
}

TEST(TriangleMesh, WeldsSharedCornersAndKeepsTriangleOrder) {
  const TriangleMesh m = TriangleMesh::weld(
      {{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}}, {{{0, 0, 0}, {1, 1, 0}, {0, 1, -0.0}}}});
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.triangles[1][0], m.triangles[0][0]);
  EXPECT_EQ(m.triangles[1][1], m.triangles[0][2]);
  EXPECT_EQ(m.non_manifold_edges(), 0u);
}

// A square of two triangles in z = 0: a sphere above their shared diagonal, or anywhere over
// them, has one contact, straight up, at its height.
TEST(MeshTouches, CoplanarTrianglesGiveOneContactEverywhere) {
  const MeshWall w =
      mesh_of({{{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}}}, {{{0, 0, 0}, {2, 2, 0}, {0, 2, 0}}}});
  for (double s = 0.02; s < 2.0; s += 0.0137) {
    for (const Vec3 c : {Vec3{s, s, 0.4}, Vec3{s, 1.0, 0.4}, Vec3{1.0, s, 0.4}}) {
      const WallTouches t = touches_of(w, c, 0.5);
      ASSERT_EQ(t.n, 1u) << "at " << c.x << ", " << c.y;
      EXPECT_NEAR(t.at[0].distance, 0.4, 1e-15);
      EXPECT_NEAR(t.at[0].normal.z, 1.0, 1e-15);
    }
  }
  // over the shared corner (0, 0, 0) from outside the square: one vertex contact
  const WallTouches corner = touches_of(w, {-0.1, -0.1, 0.1}, 0.5);
  ASSERT_EQ(corner.n, 1u);
  EXPECT_NEAR(corner.at[0].distance, std::sqrt(0.03), 1e-15);
}

// A fan of triangles around a vertex: a sphere right over it has one contact.
TEST(MeshTouches, AFanAroundAVertexGivesOneContact) {
  std::vector<std::array<Vec3, 3>> fan;
  for (int k = 0; k < 7; ++k) {
    const double a0 = 2 * std::numbers::pi * k / 7, a1 = 2 * std::numbers::pi * (k + 1) / 7;
    fan.push_back({{{0, 0, 0}, {std::cos(a0), std::sin(a0), 0}, {std::cos(a1), std::sin(a1), 0}}});
  }
  const MeshWall w = mesh_of(fan);
  const WallTouches t = touches_of(w, {0, 0, 0.3}, 0.5);
  ASSERT_EQ(t.n, 1u);
  EXPECT_NEAR(t.at[0].distance, 0.3, 1e-15);
}

// A 90 degree groove (faces x = z and x = -z below z = 0... as two triangles pairs): a sphere
// in it touches both faces; a sphere over a convex ridge touches once, with a normal that turns
// continuously and a distance that stays put as it rounds the ridge.
TEST(MeshTouches, GrooveGivesTwoContactsRidgeOne) {
  // faces through the line x = 0, z = 0 along y, at 45 degrees
  const double L = 3;
  const std::vector<std::array<Vec3, 3>> groove{{{{0, -L, 0}, {L, -L, L}, {L, L, L}}},
                                                {{{0, -L, 0}, {L, L, L}, {0, L, 0}}},
                                                {{{0, -L, 0}, {0, L, 0}, {-L, L, L}}},
                                                {{{0, -L, 0}, {-L, L, L}, {-L, -L, L}}}};
  const MeshWall g = mesh_of(groove);
  const WallTouches in = touches_of(g, {0, 0.1, 0.6}, 0.5);
  ASSERT_EQ(in.n, 2u);
  EXPECT_NEAR(in.at[0].distance, 0.6 / std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(dot(in.at[0].normal, in.at[1].normal), 0.0, 1e-14);
  // the ridge: the same faces seen from below
  double last_nx = -1;
  const double h = 0.3;
  for (double s = -1.0; s <= 1.0; s += 0.001) {
    // a path at distance h from the surface: over face x < 0, around the edge, over x > 0
    const double phi = std::clamp(s, -0.25, 0.25) * std::numbers::pi; // normal's angle
    Vec3 c{std::sin(phi) * h, 0.0, -std::cos(phi) * h};
    if (s < -0.25) c = c + (s + 0.25) * Vec3{1, 0, -1} * (1 / std::sqrt(2.0));
    if (s > 0.25) c = c + (s - 0.25) * Vec3{1, 0, 1} * (1 / std::sqrt(2.0));
    const WallTouches t = touches_of(g, c, 0.5);
    ASSERT_EQ(t.n, 1u) << "s = " << s;
    EXPECT_NEAR(t.at[0].distance, h, 1e-12) << "s = " << s;
    EXPECT_GE(t.at[0].normal.x, last_nx - 1e-12);
    EXPECT_LT(std::abs(t.at[0].normal.x - last_nx), last_nx < -0.99 ? 2.0 : 0.01);
    last_nx = t.at[0].normal.x;
  }
}

TEST(MeshTouches, ConveyorMovesTheSurfaceAlongTheWall) {
  MeshWall w = mesh_of({{{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}}}});
  w.surface_velocity = {1.5, 0, 7}; // the part along the normal is dropped
  const WallTouches t = touches_of(w, {1.5, 0.5, 0.2}, 0.5);
  ASSERT_EQ(t.n, 1u);
  EXPECT_EQ(t.at[0].velocity, (Vec3{1.5, 0, 0}));
}

TEST(CylinderTouches, InsideOutsideCapsAndRims) {
  CylinderWall c;
  c.radius = 2;
  c.lo = 0, c.hi = 5, c.capped = true;
  // inside, against the side
  WallTouches t;
  c.touches({1.7, 0, 2.5}, 0.5, t);
  ASSERT_EQ(t.n, 1u);
  EXPECT_NEAR(t.at[0].distance, 0.3, 1e-15);
  EXPECT_NEAR(t.at[0].normal.x, -1, 1e-15);
  // in the corner of side and floor: both
  c.touches({1.7, 0, 0.4}, 0.5, t);
  ASSERT_EQ(t.n, 2u);
  EXPECT_NEAR(t.at[0].distance, 0.3, 1e-15);
  EXPECT_NEAR(t.at[1].distance, 0.4, 1e-15);
  // outside a post, capped: over the top, and past the rim
  c.inside = false;
  c.touches({0.5, 0, 5.3}, 0.5, t);
  ASSERT_EQ(t.n, 1u);
  EXPECT_NEAR(t.at[0].normal.z, 1, 1e-15);
  c.touches({2.2, 0, 5.2}, 0.5, t);
  ASSERT_EQ(t.n, 1u);
  EXPECT_NEAR(t.at[0].distance, std::sqrt(0.08), 1e-15);
  // the side turns: the wall's velocity at the contact is omega k x (p - c)
  c.omega = 3;
  c.touches({2.3, 0, 2}, 0.5, t);
  ASSERT_EQ(t.n, 1u);
  EXPECT_NEAR(t.at[0].velocity.y, 6.0, 1e-14);
}

TEST(RigidMotion, VelocityIsTheDerivativeOfPosition) {
  RigidMotion m;
  m.center = {1, 2, 3};
  m.axis = normalized(Vec3{1, 2, 2});
  m.omega = 1.7;
  m.drift = {0.1, -0.2, 0.3};
  m.direction = {0, 0, 1};
  m.amplitude = 0.05;
  m.frequency = 9;
  m.t0 = 0.5;
  const Vec3 rest{-1, 0.5, 2};
  for (double t : {0.7, 1.3, 4.0}) {
    const double h = 1e-6;
    const Vec3 fd =
        (m.at_time(t + h).place(rest).position - m.at_time(t - h).place(rest).position) / (2 * h);
    EXPECT_LT(norm(fd - m.at_time(t).place(rest).velocity), 1e-7);
    // a rotation keeps distances to the axis
    const Vec3 p = m.at_time(t).place(rest).position - m.at_time(t).shift;
    EXPECT_NEAR(norm(cross(p - m.center, m.axis)), norm(cross(rest - m.center, m.axis)), 1e-12);
  }
  EXPECT_EQ(m.at_time(0.2).place(rest).position, rest);
  // Stopped at t1: held where it was then, at rest.
  m.t1 = 2.0;
  const PlacedState at_stop = m.at_time(2.0 - 1e-12).place(rest);
  for (double t : {2.0, 3.0, 40.0}) {
    const PlacedState held = m.at_time(t).place(rest);
    EXPECT_LT(norm(held.position - at_stop.position), 1e-10);
    EXPECT_EQ(held.velocity, Vec3{});
  }
}

} // namespace
} // namespace yuxi
