// Coarse-graining on a cylindrical grid held to the Cartesian one and to integrals: at every point
// of an (r, theta, z) grid the fields are the Cartesian fields at that point, turned into the
// point's basis; the mean around a circle is the function's mean by independent quadrature;
// plain bins hold the grains' mass and the contacts' virial f . b and f_z b_z, which no rotation
// about the axis changes.
#include "analysis/cg_cylinder.hpp"
#include "core/random.hpp"

#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace yuxi::analysis {
namespace {

constexpr double pi = std::numbers::pi;

// Grains about the axis x = y = 2 (within r < 1.8, 0 < z < 3), and contacts between neighbours
// (with arbitrary forces) and with walls.
struct System {
  std::vector<Vec3> x, v;
  std::vector<double> mass, volume;
  std::vector<CgContact> contacts;
  CgGrains view() const { return {x, v, mass, volume}; }
};

System random_system(std::uint64_t seed) {
  Random random(seed);
  System s;
  for (int i = 0; i < 150; ++i) {
    const double r = 1.8 * std::sqrt(random.uniform(0, 1)), t = random.uniform(0, 2 * pi);
    s.x.push_back({2 + r * std::cos(t), 2 + r * std::sin(t), random.uniform(0.2, 2.8)});
    s.v.push_back({random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)});
    s.mass.push_back(random.uniform(0.5, 2));
    s.volume.push_back(random.uniform(0.01, 0.05));
  }
  for (std::size_t a = 0; a < s.x.size(); ++a)
    for (std::size_t b = a + 1; b < s.x.size(); ++b)
      if (norm(s.x[a] - s.x[b]) < 0.6) {
        const Vec3 branch = s.x[a] - s.x[b];
        const Vec3 f{random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)};
        s.contacts.push_back({s.x[a], s.volume[a], false, s.volume[b], f, branch,
                              s.x[b] + branch * 0.5, random.uniform(0, 0.1)});
      }
  for (std::size_t a = 0; a < s.x.size(); a += 7) {
    const Vec3 point{s.x[a].x, s.x[a].y, 0.0};
    s.contacts.push_back(
        {s.x[a], s.volume[a], true, 0.0, {0.1, -0.2, 1.0}, s.x[a] - point, point, 0.01});
  }
  return s;
}

// The rows e_r, e_theta, e_z at angle t.
std::array<Vec3, 3> basis(double t) {
  return {Vec3{std::cos(t), std::sin(t), 0.0}, Vec3{-std::sin(t), std::cos(t), 0.0},
          Vec3{0.0, 0.0, 1.0}};
}

// A function of width 0.3 (cut off at 3 w) on a grid about the grains' axis: r < 2, 0 < z < 3.
CgCylinderSettings about_the_grains(CgKind kind, std::array<int, 3> n, bool theta_averaged) {
  CgCylinderSettings s;
  s.kind = kind;
  s.width = 0.3;
  s.cutoff = 3 * s.width;
  s.grid = {2.0, 2.0, 0.0, 2.0, 0.0, 3.0, n, theta_averaged, false};
  return s;
}

// (With z averaged over [0.5, 2.5], against a Cartesian grid averaged over the same span.)
TEST(CoarseGrainCylinder, FieldsAtEachPointAreTheCartesianFieldsThereInItsBasis) {
  const System sys = random_system(3);
  for (const bool z_averaged : {false, true})
    for (const CgKind kind : {CgKind::gaussian, CgKind::lucy}) {
      CgCylinderSettings s = about_the_grains(kind, {5, 7, 4}, false);
      if (z_averaged)
        s.grid.z_lo = 0.5, s.grid.z_hi = 2.5, s.grid.n[2] = 1, s.grid.z_averaged = true;
      const CgFields cyl = coarse_grain(sys.view(), sys.contacts, s);
      double largest = 0.0;
      for (const double d : cyl.contact_stress) largest = std::max(largest, std::abs(d));
      for (int k = 0; k < s.grid.n[2]; ++k)
        for (int j = 0; j < s.grid.n[1]; ++j)
          for (int i = 0; i < s.grid.n[0]; ++i) {
            const double t = s.grid.theta(j), r = s.grid.r(i);
            const Vec3 p{2 + r * std::cos(t), 2 + r * std::sin(t), s.grid.z(k)};
            // A Cartesian grid of one point, at p.
            CgSettings c;
            c.kind = kind;
            c.width = s.width;
            c.cutoff = s.cutoff;
            c.grid = {p - Vec3{0.01, 0.01, 0.01}, p + Vec3{0.01, 0.01, 0.01}, {1, 1, 1}, {}, {}};
            if (z_averaged) c.grid.lo.z = 0.5, c.grid.hi.z = 2.5, c.grid.averaged[2] = true;
            const CgFields cart = coarse_grain(sys.view(), sys.contacts, c);
            const std::size_t q = s.grid.index(i, j, k);
            const auto e = basis(t);
            EXPECT_NEAR(cyl.density[q], cart.density[0], 1e-12 * (1 + cart.density[0]));
            EXPECT_NEAR(cyl.coordination[q], cart.coordination[0], 1e-12);
            EXPECT_NEAR(cyl.elastic_energy[q], cart.elastic_energy[0], 1e-12);
            for (int a = 0; a < 3; ++a) {
              const Vec3 momentum{cart.momentum[0], cart.momentum[1], cart.momentum[2]};
              EXPECT_NEAR(cyl.momentum[3 * q + a], dot(e[a], momentum), 1e-12);
              for (int b = 0; b < 3; ++b) {
                double turned = 0.0;
                for (int m = 0; m < 3; ++m)
                  for (int n = 0; n < 3; ++n)
                    turned += e[a][m] * cart.contact_stress[3 * m + n] * e[b][n];
                EXPECT_NEAR(cyl.contact_stress[9 * q + 3 * a + b], turned, 1e-12 * largest)
                    << to_string(kind) << " at point " << q;
              }
            }
          }
    }
}

TEST(CoarseGrainCylinder, MeanAroundTheCircleIsTheFunctionsMean) {
  const System sys = random_system(4);
  for (const CgKind kind : {CgKind::gaussian, CgKind::lucy}) {
    const CgCylinderSettings s = about_the_grains(kind, {6, 1, 5}, true);
    const CgFields f = coarse_grain(sys.view(), {}, s);
    const CgFunction phi(kind, s.width, s.cutoff, 3);
    double largest = 0.0;
    for (const double d : f.density) largest = std::max(largest, d);
    for (int k = 0; k < s.grid.n[2]; ++k)
      for (int i = 0; i < s.grid.n[0]; ++i) {
        // (1 / 2 pi) times the integral over theta of sum m phi: Simpson's rule, 20,000 panels.
        const double r = s.grid.r(i), z = s.grid.z(k);
        const auto density = [&](double t) {
          double sum = 0.0;
          for (std::size_t g = 0; g < sys.x.size(); ++g)
            sum += sys.mass[g] *
                   phi.at(norm2(Vec3{2 + r * std::cos(t), 2 + r * std::sin(t), z} - sys.x[g]));
          return sum;
        };
        const int panels = 20000;
        double simpson = density(0.0) + density(2 * pi);
        for (int m = 1; m < panels; ++m)
          simpson += density(2 * pi * m / panels) * (m % 2 ? 4.0 : 2.0);
        simpson *= (2 * pi / panels) / 3.0 / (2 * pi);
        EXPECT_NEAR(f.density[s.grid.index(i, 0, k)], simpson, 1e-5 * largest)
            << to_string(kind) << " at r = " << r << ", z = " << z;
      }
  }
}

TEST(CoarseGrainCylinder, BinsHoldTheMassAndTheVirial) { // theta and z resolved or averaged
  const System sys = random_system(5);
  double mass = 0.0, trace = 0.0, zz = 0.0;
  for (const double m : sys.mass) mass += m;
  for (const CgContact& c : sys.contacts)
    trace += dot(c.force, c.branch), zz += c.force.z * c.branch.z;
  for (const bool theta_averaged : {false, true})
    for (const bool z_averaged : {false, true}) {
      CgCylinderSettings s;
      s.kind = CgKind::bins;
      s.grid = {2.0,
                2.0,
                0.0,
                2.5,
                -0.5,
                3.5,
                {7, theta_averaged ? 1 : 9, z_averaged ? 1 : 6},
                theta_averaged,
                z_averaged};
      const CgFields f = coarse_grain(sys.view(), sys.contacts, s);
      double grid_mass = 0.0, grid_trace = 0.0, grid_zz = 0.0;
      for (int k = 0; k < s.grid.n[2]; ++k)
        for (int j = 0; j < s.grid.n[1]; ++j)
          for (int i = 0; i < s.grid.n[0]; ++i) {
            const std::size_t q = s.grid.index(i, j, k);
            const double volume = s.grid.cell_volume(i);
            grid_mass += f.density[q] * volume;
            grid_trace += (f.contact_stress[9 * q] + f.contact_stress[9 * q + 4] +
                           f.contact_stress[9 * q + 8]) *
                          volume;
            grid_zz += f.contact_stress[9 * q + 8] * volume;
          }
      EXPECT_NEAR(grid_mass, mass, 1e-12 * mass) << "theta averaged " << theta_averaged;
      EXPECT_NEAR(grid_trace, trace, 1e-12 * std::abs(trace))
          << "theta averaged " << theta_averaged;
      EXPECT_NEAR(grid_zz, zz, 1e-12 * std::abs(zz)) << "theta averaged " << theta_averaged;
    }
}

TEST(CoarseGrainCylinder, RefusesImpossibleGrids) {
  CgCylinder g{0, 0, 0, 1, 0, 1, {2, 2, 2}, false, false};
  g.r_lo = -1;
  EXPECT_THROW(g.check(), std::invalid_argument);
  g.r_lo = 0, g.z_hi = 0;
  EXPECT_THROW(g.check(), std::invalid_argument);
  g.z_hi = 1, g.theta_averaged = true;
  EXPECT_THROW(g.check(), std::invalid_argument);
  g.n[1] = 1;
  EXPECT_NO_THROW(g.check());
}

} // namespace
} // namespace yuxi::analysis
