// A clump's volume, centre of mass and inertia (scene/sphere_union.hpp, scene/clump_shape.hpp)
// against closed forms. Spheres on one axis are exact: each slice across the axis is the widest
// member's disc, so the union is a stack of pieces of spheres whose moments are polynomials.
// Turned off the axis, the same clump exercises the general slices (arcs of several circles);
// a random clump in three orientations must give the same principal moments, and a Monte Carlo
// estimate bounds it independently.
#include "core/quaternion.hpp"
#include "core/symmetric_eigen3.hpp"
#include "core/units.hpp"
#include "scene/clump_shape.hpp"
#include "scene/sphere_union.hpp"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <stdexcept>
#include <vector>

namespace yuxi {
namespace {

// The moments of the piece z0 <= z <= z1 of a sphere of radius r centred at (0, 0, c), from
// the antiderivatives in u = z - c of pi rho^2, z pi rho^2, z^2 pi rho^2 and pi rho^4 / 4
// (the disc's integral of x^2), rho^2 = r^2 - u^2.
struct AxialMoments {
  double volume = 0, z = 0, zz = 0, xx = 0;
  AxialMoments& operator+=(const AxialMoments& o) {
    volume += o.volume, z += o.z, zz += o.zz, xx += o.xx;
    return *this;
  }
};
AxialMoments sphere_piece(double r, double c, double z0, double z1) {
  const auto at = [&](double z) {
    const double u = z - c, r2 = r * r;
    const double f0 = r2 * u - u * u * u / 3;                                    // rho^2
    const double f1 = r2 * u * u / 2 - u * u * u * u / 4;                        // u rho^2
    const double f2 = r2 * u * u * u / 3 - std::pow(u, 5) / 5;                   // u^2 rho^2
    const double f4 = r2 * r2 * u - 2 * r2 * u * u * u / 3 + std::pow(u, 5) / 5; // rho^4
    return AxialMoments{pi * f0, pi * (f1 + c * f0), pi * (f2 + 2 * c * f1 + c * c * f0),
                        pi / 4 * f4};
  };
  const AxialMoments hi = at(z1), lo = at(z0);
  return {hi.volume - lo.volume, hi.z - lo.z, hi.zz - lo.zz, hi.xx - lo.xx};
}

// Spheres on the z axis (centres ascending, each overlapping only its neighbours): the union
// is each sphere's piece between the heights where its disc and its neighbours' are equal.
AxialMoments axial_union(const std::vector<SphereMember>& s) {
  AxialMoments m;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double c = s[k].centre.z, r = s[k].radius;
    double lo = c - r, hi = c + r;
    const auto equal_discs = [](const SphereMember& a, const SphereMember& b) {
      const double d = b.centre.z - a.centre.z;
      return a.centre.z + (d * d + a.radius * a.radius - b.radius * b.radius) / (2 * d);
    };
    if (k > 0) lo = std::max(lo, equal_discs(s[k - 1], s[k]));
    if (k + 1 < s.size()) hi = std::min(hi, equal_discs(s[k], s[k + 1]));
    m += sphere_piece(r, c, lo, hi);
  }
  return m;
}

double relative(double a, double b) {
  return std::abs(a - b) / std::abs(b);
}

TEST(SphereUnion, OneSphereAnywhere) {
  const SphereMember s{{0.3, -1.2, 2.5}, 0.7};
  const VolumeMoments m = sphere_union_moments(std::span(&s, 1));
  const double v = 4.0 / 3.0 * pi * std::pow(0.7, 3);
  EXPECT_LT(relative(m.volume, v), 1e-14);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LT(relative(m.first[a], v * s.centre[a]), 1e-14);
    for (int b = 0; b < 3; ++b) {
      const double central = (a == b ? v * 0.49 / 5 : 0.0);
      EXPECT_NEAR(m.second[a][b], central + v * s.centre[a] * s.centre[b], 1e-14 * v * 8) << a << b;
    }
  }
}

TEST(SphereUnion, OverlappingSpheresOnAnAxisMatchTheClosedForm) {
  // Two unequal spheres, and a chain of three (only neighbours overlap).
  const std::vector<std::vector<SphereMember>> clumps{
      {{{0, 0, 0}, 1.0}, {{0, 0, 1.3}, 0.6}},
      {{{0, 0, -0.8}, 0.5}, {{0, 0, 0.0}, 0.5}, {{0, 0, 0.8}, 0.5}},
  };
  for (const auto& members : clumps) {
    const VolumeMoments m = sphere_union_moments(members);
    const AxialMoments exact = axial_union(members);
    EXPECT_LT(relative(m.volume, exact.volume), 1e-13);
    EXPECT_NEAR(m.first.z, exact.z, 1e-13 * exact.volume);
    EXPECT_NEAR(m.first.x, 0.0, 1e-13 * exact.volume);
    EXPECT_LT(relative(m.second[2][2], exact.zz), 1e-13);
    EXPECT_LT(relative(m.second[0][0], exact.xx), 1e-13);
    EXPECT_LT(relative(m.second[1][1], exact.xx), 1e-13);
    EXPECT_NEAR(m.second[0][1], 0.0, 1e-13 * exact.xx);
  }
}

// The clump's shape for members turned by q about the origin and moved by shift.
std::vector<SphereMember> moved(const std::vector<SphereMember>& members, const Quaternion& q,
                                const Vec3& shift) {
  std::vector<SphereMember> out;
  for (const SphereMember& m : members) out.push_back({to_lab(q, m.centre) + shift, m.radius});
  return out;
}

// The shape's members, in its principal frame, centred with a diagonal inertia tensor whose
// entries are the principal moments: a wrong (transposed, reflected) frame fails this.
void expect_principal(const ClumpShape& s) {
  const VolumeMoments m = sphere_union_moments(s.members);
  const double scale = s.inertia_per_density.z;
  const double size = std::sqrt(scale / s.volume);
  EXPECT_LT(norm(m.first) / (s.volume * size), 1e-12);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      const double inertia =
          (a == b ? m.second[0][0] + m.second[1][1] + m.second[2][2] : 0.0) - m.second[a][b];
      const double expected = a == b ? s.inertia_per_density[a] : 0.0;
      EXPECT_NEAR(inertia, expected, 1e-12 * scale) << a << b;
    }
}

TEST(ClumpShape, TurnedOffTheAxisTheShapeKeepsTheClosedForm) {
  const std::vector<SphereMember> chain{
      {{0, 0, -0.8}, 0.5}, {{0, 0, 0.0}, 0.5}, {{0, 0, 0.9}, 0.7}};
  const AxialMoments exact = axial_union(chain);
  const double zc = exact.z / exact.volume;
  const double axial = 2 * exact.xx / exact.volume;                                    // I_zz / V
  const double across = (exact.xx + exact.zz - exact.volume * zc * zc) / exact.volume; // I_xx / V
  const Quaternion q = normalized(Quaternion{0.3, -0.5, 0.7, 0.2});
  const ClumpShape s = make_clump_shape("chain", moved(chain, q, {2.0, -1.0, 0.5}));
  EXPECT_LT(relative(s.volume, exact.volume), 1e-13);
  const Vec3 centre = to_lab(q, {0, 0, zc}) + Vec3{2.0, -1.0, 0.5};
  EXPECT_LT(norm(s.centre - centre), 1e-13);
  // An axisymmetric body: the axial moment is the smallest, the other two equal.
  EXPECT_LT(relative(s.inertia_per_density.x / s.volume, axial), 1e-12);
  EXPECT_LT(relative(s.inertia_per_density.y / s.volume, across), 1e-12);
  EXPECT_LT(relative(s.inertia_per_density.z / s.volume, across), 1e-12);
  // The principal frame: the members, turned back by the frame and moved by the centre, are
  // the given ones.
  const auto given = moved(chain, q, {2.0, -1.0, 0.5});
  for (std::size_t k = 0; k < given.size(); ++k)
    EXPECT_LT(norm(to_lab(s.frame, s.members[k].centre) + s.centre - given[k].centre), 1e-13);
  // In the principal frame the members' union has its centre at the origin and a diagonal
  // tensor of the principal moments.
  expect_principal(s);
  // The axis of the smallest moment is the chain's.
  EXPECT_NEAR(std::abs(dot(to_lab(s.frame, {1, 0, 0}), to_lab(q, {0, 0, 1}))), 1.0, 1e-12);
}

std::vector<SphereMember> random_clump(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.6, 0.6), r(0.3, 0.6);
  std::vector<SphereMember> members;
  for (int k = 0; k < n; ++k) members.push_back({{u(rng), u(rng), u(rng)}, r(rng)});
  return members;
}

TEST(ClumpShape, ARandomClumpHasTheSameMomentsInEveryOrientation) {
  const auto members = random_clump(7, 2026);
  const ClumpShape a = make_clump_shape("a", members);
  for (const Quaternion& q :
       {normalized(Quaternion{1, 2, 3, 4}), normalized(Quaternion{-0.2, 0.1, 1, 0.05}),
        about_axis({0, 0, 1}, 0.5 * pi)}) {
    const ClumpShape b = make_clump_shape("b", moved(members, q, {0.3, 0.1, -0.4}));
    EXPECT_LT(relative(b.volume, a.volume), 1e-13);
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(relative(b.inertia_per_density[k], a.inertia_per_density[k]), 1e-12) << k;
    EXPECT_LT(norm(b.centre - (to_lab(q, a.centre) + Vec3{0.3, 0.1, -0.4})), 1e-13);
    expect_principal(b);
  }
}

TEST(ClumpShape, ARandomClumpAgreesWithMonteCarlo) {
  const auto members = random_clump(7, 2026);
  const ClumpShape s = make_clump_shape("a", members);
  // Points uniform in the box about the members; the hits estimate the volume and the centre.
  Vec3 lo{1e9, 1e9, 1e9}, hi{-1e9, -1e9, -1e9};
  for (const SphereMember& m : members)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], m.centre[a] - m.radius);
      hi[a] = std::max(hi[a], m.centre[a] + m.radius);
    }
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = 2000000;
  int hits = 0;
  Vec3 sum;
  for (int k = 0; k < n; ++k) {
    const Vec3 p{lo.x + (hi.x - lo.x) * u(rng), lo.y + (hi.y - lo.y) * u(rng),
                 lo.z + (hi.z - lo.z) * u(rng)};
    for (const SphereMember& m : members)
      if (norm2(p - m.centre) < m.radius * m.radius) {
        ++hits;
        sum += p;
        break;
      }
  }
  const double box = (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z);
  const double f = static_cast<double>(hits) / n;
  const double sigma = box * std::sqrt(f * (1 - f) / n); // the estimate's standard deviation
  EXPECT_NEAR(s.volume, box * f, 5 * sigma);
  EXPECT_LT(norm(s.centre - sum / hits), 5e-3);
}

TEST(ClumpShape, RepeatedAndEnclosedMembersCountOnce) {
  const std::vector<SphereMember> pair{{{0, 0, 0}, 1.0}, {{0.9, 0.2, 0}, 0.8}};
  auto more = pair;
  more.push_back(pair[1]);                // the same member twice
  more.push_back({{0.1, 0.0, 0.1}, 0.3}); // a member inside another
  const ClumpShape a = make_clump_shape("a", pair), b = make_clump_shape("b", more);
  EXPECT_EQ(b.members.size(), 2u); // (left out: they would stiffen the contacts)
  EXPECT_LT(relative(b.volume, a.volume), 1e-13);
  for (int k = 0; k < 3; ++k)
    EXPECT_LT(relative(b.inertia_per_density[k], a.inertia_per_density[k]), 1e-12);
}

TEST(ClumpShape, MembersEqualToRoundOffCountOnce) {
  // Centres an ulp apart or less: the same member written twice by two routes.
  const std::vector<SphereMember> one{{{0, 0, 0}, 2.0}};
  for (const double gap : {1e-20, 1e-16, 6e-17}) {
    const std::vector<SphereMember> two{{{0, 0, 0}, 2.0}, {{gap, 0, 0}, 2.0}};
    EXPECT_LT(relative(sphere_union_moments(two).volume, sphere_union_moments(one).volume), 1e-14)
        << gap;
  }
}

TEST(ClumpShape, EveryAllowedSizeGivesTheSameShape) {
  const auto members = random_clump(5, 21);
  const ClumpShape unit = make_clump_shape("unit", members);
  for (const double f : {1e-45, 1e-20, 1e20, 1e45}) {
    std::vector<SphereMember> scaled;
    for (const SphereMember& m : members) scaled.push_back({m.centre * f, m.radius * f});
    const ClumpShape s = make_clump_shape("scaled", scaled);
    EXPECT_LT(relative(s.volume, unit.volume * f * f * f), 1e-13) << f;
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(relative(s.inertia_per_density[k], unit.inertia_per_density[k] * std::pow(f, 5)),
                1e-12)
          << f;
    EXPECT_NEAR(std::abs(dot(s.frame, unit.frame)), 1.0, 1e-12) << f;
  }
}

TEST(ClumpShape, ApartMembersAddUp) {
  const std::vector<SphereMember> apart{{{-1, 0, 0}, 0.5}, {{1, 0, 0}, 0.5}};
  const ClumpShape s = make_clump_shape("dumbbell", apart);
  const double v = 4.0 / 3.0 * pi * 0.125;
  EXPECT_LT(relative(s.volume, 2 * v), 1e-14);
  EXPECT_LT(relative(s.inertia_per_density.x, 2 * v * 0.1), 1e-13);
  EXPECT_LT(relative(s.inertia_per_density.y, 2 * v * (0.1 + 1.0)), 1e-13);
  EXPECT_LT(relative(s.inertia_per_density.z, 2 * v * (0.1 + 1.0)), 1e-13);
  EXPECT_NEAR(s.bounding_radius, 1.5, 1e-14);
}

TEST(ClumpShape, FarFromTheOriginTheMomentsKeepTheirDigits) {
  const auto members = random_clump(5, 9);
  const ClumpShape near = make_clump_shape("near", members);
  const ClumpShape far = make_clump_shape("far", moved(members, Quaternion{}, {1e8, -3e7, 5e6}));
  // The moved centres themselves carry the rounding of coordinates near 10^8 (1.5e-8), about
  // 3e-8 of a member's offset; computed about the far origin, the moments would keep no digit.
  EXPECT_LT(relative(far.volume, near.volume), 1e-7);
  for (int k = 0; k < 3; ++k)
    EXPECT_LT(relative(far.inertia_per_density[k], near.inertia_per_density[k]), 1e-7) << k;
}

TEST(ClumpShape, AMemberTooSmallForItsClumpIsNamed) {
  const std::vector<SphereMember> bad{{{0, 0, 0}, 1.0}, {{1, 0, 0}, 1e-9}};
  EXPECT_THROW(make_clump_shape("dust", bad), std::invalid_argument);
  const std::vector<SphereMember> tiny{{{0, 0, 0}, 1e-60}}, huge{{{0, 0, 0}, 1e60}};
  EXPECT_THROW(make_clump_shape("tiny", tiny), std::invalid_argument);
  EXPECT_THROW(make_clump_shape("huge", huge), std::invalid_argument);
}

TEST(ClumpShape, ScalingGoesAsTheLengthsPowers) {
  const ClumpShape s = make_clump_shape("a", random_clump(4, 3));
  const ClumpShape t = s.scaled(2.0);
  EXPECT_DOUBLE_EQ(t.volume, 8 * s.volume);
  EXPECT_DOUBLE_EQ(t.inertia_per_density.z, 32 * s.inertia_per_density.z);
  EXPECT_DOUBLE_EQ(t.members[0].radius, 2 * s.members[0].radius);
}

TEST(ClumpShape, AMemberWithoutARadiusIsNamed) {
  const std::vector<SphereMember> bad{{{0, 0, 0}, 1.0}, {{1, 0, 0}, 0.0}};
  try {
    make_clump_shape("rod", bad);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("shape \"rod\", member 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make_clump_shape("none", std::vector<SphereMember>{}), std::invalid_argument);
}

TEST(SymmetricEigen3, DiagonalisesARandomSymmetricMatrix) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 100; ++trial) {
    std::array<std::array<double, 3>, 3> a{};
    for (int r = 0; r < 3; ++r)
      for (int c = r; c < 3; ++c) a[r][c] = a[c][r] = u(rng);
    const SymmetricEigen3 e = symmetric_eigen3(a);
    EXPECT_LE(e.values[0], e.values[1]);
    EXPECT_LE(e.values[1], e.values[2]);
    for (int k = 0; k < 3; ++k)
      for (int r = 0; r < 3; ++r) {
        double av = 0;
        for (int c = 0; c < 3; ++c) av += a[r][c] * e.axes[k][c];
        EXPECT_NEAR(av, e.values[k] * e.axes[k][r], 1e-14);
      }
    // Orthonormal and right-handed.
    const auto as_vec = [&](int k) { return Vec3{e.axes[k][0], e.axes[k][1], e.axes[k][2]}; };
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < 3; ++l) EXPECT_NEAR(dot(as_vec(k), as_vec(l)), k == l ? 1.0 : 0.0, 1e-14);
    EXPECT_NEAR(dot(cross(as_vec(0), as_vec(1)), as_vec(2)), 1.0, 1e-14);
  }
}

TEST(SymmetricEigen3, ScaledFarFromOneItStillDiagonalises) {
  const std::array<std::array<double, 3>, 3> a{{{2, 1, 0}, {1, 3, 1}, {0, 1, 4}}};
  const SymmetricEigen3 unit = symmetric_eigen3(a);
  for (const double f : {1e-200, 1e200}) {
    std::array<std::array<double, 3>, 3> b = a;
    for (auto& row : b)
      for (double& x : row) x *= f;
    const SymmetricEigen3 e = symmetric_eigen3(b);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(relative(e.values[k], unit.values[k] * f), 1e-14) << f;
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(e.axes[k][r], unit.axes[k][r], 1e-14);
    }
  }
}

} // namespace
} // namespace yuxi
