// Regions and size distributions, the two pieces every source and measurement shares: exact
// volumes and membership against closed forms, uniform sampling (the fraction of samples in a
// part equals the part's share of the volume), a closed mesh's inside against the box it
// describes, and each distribution's moments against their analytic values.
#include "scene/region.hpp"
#include "scene/size_distribution.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

namespace yuxi {
namespace {

constexpr double pi = std::numbers::pi;
const Box big{{-100, -100, -100}, {100, 100, 100}};

// The 12 triangles of the box [lo, hi], outward normals.
TriangleMesh box_mesh(const Vec3& lo, const Vec3& hi) {
  std::vector<std::array<Vec3, 3>> soup;
  const auto corner = [&](int i) {
    return Vec3{(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
  };
  // each face as a quad of corner indices, counter-clockwise seen from outside
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    soup.push_back({corner(f[0]), corner(f[1]), corner(f[2])});
    soup.push_back({corner(f[0]), corner(f[2]), corner(f[3])});
  }
  return TriangleMesh::weld(soup);
}

TEST(Region, AnalyticVolumesAndMembership) {
  const Region box(BoxRegion{{0, 0, 0}, {2, 3, 4}});
  EXPECT_DOUBLE_EQ(box.volume_in(big), 24.0);
  EXPECT_TRUE(box.contains({1, 1, 1}));
  EXPECT_FALSE(box.contains({1, 1, 4.5}));
  EXPECT_TRUE(box.contains_sphere({1, 1, 1}, 0.9));
  EXPECT_FALSE(box.contains_sphere({1, 1, 1}, 1.1));

  const Region cyl(CylinderRegion{{0, 0, 0}, {0, 0, 1}, 2.0, -1.0, 3.0});
  EXPECT_NEAR(cyl.volume_in(big), pi * 4 * 4, 1e-12);
  EXPECT_TRUE(cyl.contains({1.9, 0, 2.9}));
  EXPECT_FALSE(cyl.contains({1.5, 1.5, 0}));
  EXPECT_TRUE(cyl.contains_sphere({1.0, 0, 0}, 1.0));
  EXPECT_FALSE(cyl.contains_sphere({1.0, 0, 2.5}, 1.0)); // through the top

  const Region ball(SphereRegion{{1, 1, 1}, 3.0});
  EXPECT_NEAR(ball.volume_in(big), 4.0 / 3.0 * pi * 27, 1e-12);
  EXPECT_TRUE(ball.contains_sphere({1, 1, 2}, 2.0));
  EXPECT_FALSE(ball.contains_sphere({1, 1, 2}, 2.1));

  // a half-space is cut by the domain: z >= 1 in [0, 10]^3
  const Region half(HalfSpaceRegion{{0, 0, 1}, {0, 0, 1}});
  const Box domain{{0, 0, 0}, {10, 10, 10}};
  EXPECT_NEAR(half.volume_in(domain), 900.0, 1e-9 * 900);
  // a slanted one, x + y + z >= 1 in the unit cube: 1 - 1/6; and x + y >= 1: 1/2
  const Box unit{{0, 0, 0}, {1, 1, 1}};
  const double s3 = 1 / std::sqrt(3.0), s2 = 1 / std::sqrt(2.0);
  EXPECT_NEAR(Region(HalfSpaceRegion{{1, 0, 0}, {s3, s3, s3}}).volume_in(unit), 5.0 / 6, 1e-12);
  EXPECT_NEAR(Region(HalfSpaceRegion{{1, 0, 0}, {-s3, -s3, -s3}}).volume_in(unit), 1.0 / 6, 1e-12);
  EXPECT_NEAR(Region(HalfSpaceRegion{{1, 0, 0.3}, {s2, s2, 0}}).volume_in(unit), 0.5, 1e-12);
  // a plane through the cube's middle at any tilt halves it
  EXPECT_NEAR(
      Region(HalfSpaceRegion{{0.5, 0.5, 0.5}, normalized({0.3, -0.7, 0.2})}).volume_in(unit), 0.5,
      1e-12);
  EXPECT_TRUE(half.contains({5, 5, 1.5}));
  EXPECT_FALSE(half.contains({5, 5, 0.5}));
}

TEST(Region, SamplesAreUniform) {
  // The share of samples of a cylinder that fall inside the inner half radius is 1/4, and of
  // a ball's within half its radius 1/8 (binomial: 3 sigma of 20000 draws < 0.01).
  Random rng(7);
  const Region cyl(CylinderRegion{{5, 5, 0}, {0, 0, 1}, 2.0, 0.0, 1.0});
  const Region ball(SphereRegion{{5, 5, 5}, 2.0});
  const int n = 20000;
  int in_cyl = 0, in_ball = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 p = *cyl.sample(rng, big);
    ASSERT_TRUE(cyl.contains(p));
    in_cyl += std::hypot(p.x - 5, p.y - 5) < 1.0;
    const Vec3 q = *ball.sample(rng, big);
    ASSERT_TRUE(ball.contains(q));
    in_ball += norm(q - Vec3{5, 5, 5}) < 1.0;
  }
  EXPECT_NEAR(in_cyl / double(n), 0.25, 0.01);
  EXPECT_NEAR(in_ball / double(n), 0.125, 0.01);
}

TEST(Region, AClosedMeshHoldsWhatItsBoxHolds) {
  const Vec3 lo{1, 2, 3}, hi{4, 4, 7};
  const Region mesh(MeshRegion(box_mesh(lo, hi)));
  const Region box(BoxRegion{lo, hi});
  EXPECT_NEAR(std::get<MeshRegion>(mesh.shape()).volume(), 24.0, 1e-12);
  Random rng(3);
  for (int i = 0; i < 5000; ++i) {
    const Vec3 p{rng.uniform(0, 5), rng.uniform(1, 5), rng.uniform(2, 8)};
    ASSERT_EQ(mesh.contains(p), box.contains(p)) << p.x << " " << p.y << " " << p.z;
    const double r = rng.uniform(0.05, 0.8);
    ASSERT_EQ(mesh.contains_sphere(p, r), box.contains_sphere(p, r));
  }
  EXPECT_NEAR(mesh.volume_in(big), 24.0, 1e-9);
}

TEST(Region, AnOpenMeshIsRefused) {
  TriangleMesh open = box_mesh({0, 0, 0}, {1, 1, 1});
  open.triangles.pop_back();
  try {
    MeshRegion region(open, "lid.stl");
    FAIL() << "an open mesh was accepted as a region";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not closed"), std::string::npos) << e.what();
  }
}

// Sample mean and mean of r^3 of a distribution.
struct Moments {
  double mean = 0, cube = 0, lo = 1e300, hi = 0;
};
Moments moments_of(const SizeDistribution& d, int n = 200000) {
  Random rng(11);
  Moments m;
  for (int i = 0; i < n; ++i) {
    const double r = d.draw(rng);
    m.mean += r / n;
    m.cube += r * r * r / n;
    m.lo = std::min(m.lo, r);
    m.hi = std::max(m.hi, r);
  }
  return m;
}

TEST(SizeDistribution, MomentsMatchTheClosedForms) {
  SizeDistribution u;
  u.kind = SizeDistribution::Kind::uniform;
  u.min = 0.5;
  u.max = 1.5;
  // <r> = 1, <r^3> = (b^4 - a^4) / 4 (b - a)
  const Moments mu = moments_of(u);
  EXPECT_NEAR(mu.mean, 1.0, 3e-3);
  EXPECT_NEAR(u.mean_cube(), (std::pow(1.5, 4) - std::pow(0.5, 4)) / 4.0, 1e-9);
  EXPECT_NEAR(mu.cube, u.mean_cube(), 0.01 * u.mean_cube());
  EXPECT_GE(mu.lo, 0.5);
  EXPECT_LE(mu.hi, 1.5);

  // lognormal with a wide truncation: the mean of the radius itself is the stated mean
  SizeDistribution ln;
  ln.kind = SizeDistribution::Kind::lognormal;
  ln.mean = 1.0;
  ln.sd = 0.2;
  ln.min = 0.2;
  ln.max = 5.0;
  const Moments ml = moments_of(ln);
  EXPECT_NEAR(ml.mean, 1.0, 3e-3);
  EXPECT_NEAR(ml.cube, ln.mean_cube(), 0.01 * ln.mean_cube());

  // normal truncated at one sd: still symmetric about the mean, inside the bounds
  SizeDistribution nm;
  nm.kind = SizeDistribution::Kind::normal;
  nm.mean = 1.0;
  nm.sd = 0.1;
  nm.min = 0.9;
  nm.max = 1.1;
  const Moments mn = moments_of(nm);
  EXPECT_NEAR(mn.mean, 1.0, 2e-3);
  EXPECT_GE(mn.lo, 0.9);
  EXPECT_LE(mn.hi, 1.1);
  EXPECT_NEAR(mn.cube, nm.mean_cube(), 0.005);
}

TEST(SizeDistribution, DiscreteWeightsByNumberOrByMass) {
  SizeDistribution d;
  d.kind = SizeDistribution::Kind::discrete;
  d.radii = {0.5, 1.0};
  d.weights = {1.0, 1.0};
  Random rng(5);
  const int n = 100000;
  double small_count = 0, small_mass = 0, mass = 0;
  for (int i = 0; i < n; ++i) {
    const double r = d.draw(rng);
    small_count += r == 0.5;
  }
  EXPECT_NEAR(small_count / n, 0.5, 0.01);
  d.by_mass = true; // half the mass in each size: 8 small grains for every large one
  small_count = 0;
  for (int i = 0; i < n; ++i) {
    const double r = d.draw(rng);
    mass += r * r * r;
    if (r == 0.5) {
      small_count += 1;
      small_mass += r * r * r;
    }
  }
  EXPECT_NEAR(small_count / n, 8.0 / 9.0, 0.01);
  EXPECT_NEAR(small_mass / mass, 0.5, 0.02);
  EXPECT_EQ(d.largest(), 1.0);
  EXPECT_EQ(d.smallest(), 0.5);
}

TEST(SizeDistribution, ImpossibleOnesAreRefusedByName) {
  const auto refusal = [](SizeDistribution d) -> std::string {
    try {
      d.validate();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  SizeDistribution d;
  d.kind = SizeDistribution::Kind::normal;
  d.mean = 1;
  d.sd = -0.1;
  d.min = 0.5;
  d.max = 1.5;
  EXPECT_NE(refusal(d).find("sd"), std::string::npos) << refusal(d);
  d.sd = 0.1;
  d.min = 2.0;
  d.max = 3.0; // keeps nothing the normal gives in practice, and min > mean
  EXPECT_NE(refusal(d), "accepted");
  d.min = 1.5;
  d.max = 0.5;
  EXPECT_NE(refusal(d).find("min"), std::string::npos) << refusal(d);
  SizeDistribution w;
  w.kind = SizeDistribution::Kind::discrete;
  w.radii = {1.0, 2.0};
  w.weights = {0.0, 0.0};
  EXPECT_NE(refusal(w).find("weights"), std::string::npos) << refusal(w);
  w.weights = {1.0};
  EXPECT_NE(refusal(w), "accepted");
  SizeDistribution c;
  c.radius = -1.0;
  EXPECT_NE(refusal(c).find("radius"), std::string::npos) << refusal(c);
}

} // namespace
} // namespace yuxi
