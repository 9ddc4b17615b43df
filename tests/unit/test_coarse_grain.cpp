// Coarse-graining held to what it must satisfy, not to its own output: the functions integrate
// to one (independent quadrature), the line integral equals brute-force quadrature, the mass on
// a grid that covers a periodic box is the grains' mass, and the fields of grains moving under
// given forces satisfy the continuum balances of mass and momentum, d rho/dt + div(rho V) = 0
// and d(rho V)/dt + div(rho V V + sigma) = t (docs/coarse-graining.md), by finite differences
// in time and space of the fields themselves.
#include "analysis/cg_accumulate.hpp"
#include "analysis/coarse_grain.hpp"
#include "analysis/erf_table.hpp"
#include "core/random.hpp"
#include "scene/coarse_grain_spec.hpp"

#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace yuxi::analysis {
namespace {

constexpr double pi = std::numbers::pi;

// Composite Simpson's rule of f on [a, b] with n (even) intervals.
template <class F> double simpson(F f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int k = 1; k < n; ++k) s += f(a + k * h) * (k % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

TEST(TableErf, IsTheLibrarysErfToRoundOff) {
  Random random(3);
  double worst = 0.0;
  for (int k = 0; k < 1000000; ++k) {
    const double x = random.uniform(-7.0, 7.0);
    worst = std::max(worst, std::abs(table_erf(x) - std::erf(x)));
  }
  EXPECT_LT(worst, 1e-15);
  for (const double x : {0.0, 1.0 / 128, 0.5, 3.0, 5.9921875, 6.0, 1e300})
    EXPECT_NEAR(table_erf(x), std::erf(x), 4e-16) << x;
  EXPECT_EQ(table_erf(-0.3), -table_erf(0.3));
  EXPECT_EQ(table_erf(INFINITY), 1.0);
  EXPECT_EQ(table_erf(-INFINITY), -1.0);
  EXPECT_TRUE(std::isnan(table_erf(NAN)));
}

TEST(CoarseGrainFunction, IntegratesToOneInEveryDimension) {
  for (const CgKind kind : {CgKind::gaussian, CgKind::lucy})
    for (int d = 1; d <= 3; ++d) {
      const double w = 0.7, c = kind == CgKind::gaussian ? 2.5 * w : 3.0 * w;
      const CgFunction phi(kind, w, c, d);
      // The d-sphere's surface: 2 (d = 1), 2 pi r (d = 2), 4 pi r^2 (d = 3).
      const double integral = simpson(
          [&](double r) {
            const double shell = d == 1 ? 2.0 : d == 2 ? 2.0 * pi * r : 4.0 * pi * r * r;
            return phi.at(r * r) * shell;
          },
          0.0, c * (1.0 - 1e-15), 20000);
      EXPECT_NEAR(integral, 1.0, 1e-9) << to_string(kind) << " in " << d << "-D";
      EXPECT_EQ(phi.at(c * c * 1.0000001), 0.0);
    }
}

TEST(CoarseGrainFunction, LineIntegralIsTheQuadratureOfTheFunction) {
  Random random(7);
  for (const CgKind kind : {CgKind::gaussian, CgKind::lucy})
    for (int d = 1; d <= 3; ++d) {
      const double w = 0.5;
      const CgFunction phi(kind, w, 3.0 * w, d);
      for (int trial = 0; trial < 50; ++trial) {
        Vec3 q{random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(-2, 2)};
        Vec3 b{random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(-2, 2)};
        if (d < 3) q.z = b.z = 0.0;
        if (d < 2) q.y = b.y = 0.0;
        const double brute =
            simpson([&](double s) { return phi.at(norm2(q - b * s)); }, 0.0, 1.0, 200000);
        EXPECT_NEAR(phi.along(q, b), brute, 1e-9 * (1.0 + std::abs(brute)))
            << to_string(kind) << " " << d << "-D, trial " << trial;
      }
    }
}

TEST(CoarseGrainFunction, LineIntegralAlongOneAxisIsTheQuadratureOfTheFunction) {
  Random random(11);
  for (const CgKind kind : {CgKind::gaussian, CgKind::lucy}) {
    const double w = 0.5;
    const CgFunction phi(kind, w, 3.0 * w, 1);
    for (int trial = 0; trial < 200; ++trial) {
      const double q = random.uniform(-2, 2);
      const double b = trial % 10 == 0 ? 0.0 : random.uniform(-2, 2);
      const double brute =
          simpson([&](double s) { return phi.at((q - b * s) * (q - b * s)); }, 0.0, 1.0, 200000);
      EXPECT_NEAR(phi.along_axis(q, b), brute, 1e-9 * (1.0 + std::abs(brute)))
          << to_string(kind) << ", trial " << trial;
      EXPECT_NEAR(phi.along_axis(q, b), phi.along({q, 0, 0}, {b, 0, 0}), 1e-12)
          << to_string(kind) << ", trial " << trial;
      // A branch's constants made once (a profile's contacts), the same integral to the
      // round-off of a difference of two erf divided by the branch's length.
      if (b != 0.0) {
        EXPECT_NEAR(CgFunction::AxisBranch(phi, b)(q), phi.along_axis(q, b),
                    4e-15 * (1.0 + std::abs(brute)) / std::min(1.0, std::abs(b)))
            << to_string(kind) << ", trial " << trial;
      }
    }
  }
}

TEST(CoarseGrainFunction, RefusesImpossibleSettings) {
  EXPECT_THROW(CgFunction(CgKind::gaussian, 0.0, 1.0, 3), std::invalid_argument);
  EXPECT_THROW(CgFunction(CgKind::lucy, 1.0, -1.0, 3), std::invalid_argument);
  EXPECT_THROW(CgFunction(CgKind::gaussian, 1.0, 3.0, 0), std::invalid_argument);
  CgGrid grid{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {false, false, false}, {false, false, false}};
  grid.hi.y = 0.0;
  EXPECT_THROW(grid.check(), std::invalid_argument);
  grid.hi.y = 1.0;
  grid.averaged = {true, true, true};
  EXPECT_THROW(grid.check(), std::invalid_argument);
}

// Random grains in the periodic box [0, 4)^3.
struct Grains {
  std::vector<Vec3> x, v;
  std::vector<double> mass, volume;
  CgGrains view() const { return {x, v, mass, volume}; }
  double total_mass() const {
    double m = 0.0;
    for (const double mi : mass) m += mi;
    return m;
  }
};
Grains random_grains(int n, std::uint64_t seed) {
  Random random(seed);
  Grains g;
  for (int i = 0; i < n; ++i) {
    g.x.push_back({random.uniform(0, 4), random.uniform(0, 4), random.uniform(0, 4)});
    g.v.push_back({random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)});
    g.mass.push_back(random.uniform(0.5, 2.0));
    g.volume.push_back(random.uniform(0.01, 0.05));
  }
  return g;
}

double grid_sum(const std::vector<double>& field, const CgGrid& grid) {
  double s = 0.0;
  for (const double f : field) s += f;
  return s * grid.cell_volume();
}

// The weights on a grid, made axis by axis (the Gaussian's exponentials by a recurrence), are the
// function at each point's distance, periodic images included, on grids of 1, 2 and 3 axes.
TEST(CoarseGrain, AGrainWeighsOnEveryPointByTheFunctionAtItsDistance) {
  Random random(5);
  for (const CgKind kind : {CgKind::gaussian, CgKind::lucy})
    for (int resolved = 1; resolved <= 3; ++resolved)
      for (const bool periodic : {false, true}) {
        CgSettings s;
        s.kind = kind;
        s.width = 0.3;
        s.cutoff = kind == CgKind::gaussian ? 9.0 * s.width : 3.0 * s.width;
        s.grid = {{0, 0, 0}, {4, 4, 4}, {13, 7, 16}, {false, false, false}, {}};
        for (int a = resolved; a < 3; ++a) {
          s.grid.averaged[static_cast<std::size_t>(a)] = true;
          s.grid.n[static_cast<std::size_t>(a)] = 1;
        }
        for (int a = 0; a < resolved; ++a) s.grid.periodic[static_cast<std::size_t>(a)] = periodic;
        const CgFunction phi(kind, s.width, s.cutoff, resolved);
        const Vec3 x{random.uniform(0, 4), random.uniform(0, 4), random.uniform(0, 4)};
        const std::vector<Vec3> xs{x}, vs{{0, 0, 0}};
        const std::vector<double> mass{1.0}, volume{0.0};
        const CgFields f = coarse_grain({xs, vs, mass, volume}, {}, s);
        double largest = 0.0;
        for (const double d : f.density) largest = std::max(largest, d);
        for (int k = 0; k < s.grid.n[2]; ++k)
          for (int j = 0; j < s.grid.n[1]; ++j)
            for (int i = 0; i < s.grid.n[0]; ++i) {
              const std::array<int, 3> at{i, j, k};
              double expected = 0.0;
              // Every image within reach on a periodic axis (the box is 4 long).
              for (int ix = periodic ? -3 : 0; ix <= (periodic ? 3 : 0); ++ix)
                for (int iy = periodic && resolved > 1 ? -3 : 0;
                     iy <= (periodic && resolved > 1 ? 3 : 0); ++iy)
                  for (int iz = periodic && resolved > 2 ? -3 : 0;
                       iz <= (periodic && resolved > 2 ? 3 : 0); ++iz) {
                    const std::array<int, 3> image{ix, iy, iz};
                    double r2 = 0.0;
                    for (int a = 0; a < resolved; ++a) {
                      const auto u = static_cast<std::size_t>(a);
                      const double d = s.grid.coordinate(a, at[u]) - (x[a] + 4.0 * image[u]);
                      r2 += d * d;
                    }
                    expected += phi.at(r2);
                  }
              expected /= s.grid.averaged_extent();
              EXPECT_NEAR(f.density[s.grid.index(i, j, k)], expected, 1e-13 * largest)
                  << to_string(kind) << ", " << resolved << " axes, periodic " << periodic;
            }
      }
}

TEST(CoarseGrain, MassOnABinGridOverAPeriodicBoxIsTheGrainsMass) {
  const Grains g = random_grains(500, 1);
  CgSettings s;
  s.kind = CgKind::bins;
  s.grid = {{0, 0, 0}, {4, 4, 4}, {5, 3, 4}, {false, false, false}, {true, true, true}};
  const CgFields f = coarse_grain(g.view(), {}, s);
  EXPECT_NEAR(grid_sum(f.density, s.grid), g.total_mass(), 1e-12 * g.total_mass());
}

TEST(CoarseGrain, MassOfAResolvedGaussianOverAPeriodicBoxIsTheGrainsMass) {
  // A Gaussian cut off where it is below round-off, sampled at half its width: the grid's sum is
  // its integral to round-off (the trapezoidal rule on a smooth periodic function).
  const Grains g = random_grains(200, 2);
  CgSettings s;
  s.kind = CgKind::gaussian;
  s.width = 0.4;
  s.cutoff = 9.0 * s.width;
  for (const auto& averaged :
       {std::array<bool, 3>{true, true, false}, std::array<bool, 3>{false, true, false},
        std::array<bool, 3>{false, false, false}}) {
    s.grid = {{0, 0, 0}, {4, 4, 4}, {20, 20, 20}, averaged, {true, true, true}};
    for (int a = 0; a < 3; ++a)
      if (averaged[static_cast<std::size_t>(a)]) s.grid.n[static_cast<std::size_t>(a)] = 1;
    const CgFields f = coarse_grain(g.view(), {}, s);
    EXPECT_NEAR(grid_sum(f.density, s.grid), g.total_mass(), 1e-11 * g.total_mass())
        << "dimension " << s.grid.dimension();
  }
}

// Grains moving under constant forces (pair forces, equal and opposite, and wall forces): the
// fields at one point, at t = -dt, 0, +dt, and at the six neighbours of the point a step h
// away, for the balances' central differences.
struct Moving {
  Grains at_zero;
  std::vector<Vec3> acceleration;
  std::vector<CgContact> contacts;
};

Moving moving_grains() {
  Random random(11);
  Moving m;
  m.at_zero = random_grains(40, 3);
  for (Vec3& x : m.at_zero.x) x = x * 0.5 + Vec3{1, 1, 1}; // within [1, 3)^3
  std::vector<Vec3> force(m.at_zero.x.size());
  for (std::size_t i = 0; i < force.size(); ++i)
    for (std::size_t j = i + 1; j < force.size(); ++j) {
      const Vec3 branch = m.at_zero.x[i] - m.at_zero.x[j];
      if (norm(branch) > 0.6) continue;
      // Any force, friction-like (not along the branch) included.
      const Vec3 f{random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)};
      force[i] += f, force[j] -= f;
      m.contacts.push_back({m.at_zero.x[i], m.at_zero.volume[i], false, m.at_zero.volume[j], f,
                            branch, m.at_zero.x[j] + branch * 0.5, 0.0});
    }
  for (std::size_t i = 0; i < 5; ++i) { // walls below five grains, their contact points 0.1 down
    const Vec3 f{random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3), random.uniform(0.5, 1)};
    const Vec3 point = m.at_zero.x[i] - Vec3{0, 0, 0.1};
    force[i] += f;
    m.contacts.push_back(
        {m.at_zero.x[i], m.at_zero.volume[i], true, 0.0, f, m.at_zero.x[i] - point, point, 0.0});
  }
  for (std::size_t i = 0; i < force.size(); ++i)
    m.acceleration.push_back(force[i] / m.at_zero.mass[i]);
  return m;
}

// The grains at time t (exact motion under constant forces).
Grains at_time(const Moving& m, double t) {
  Grains g = m.at_zero;
  for (std::size_t i = 0; i < g.x.size(); ++i) {
    g.x[i] = m.at_zero.x[i] + m.at_zero.v[i] * t + m.acceleration[i] * (0.5 * t * t);
    g.v[i] = m.at_zero.v[i] + m.acceleration[i] * t;
  }
  return g;
}

// The fields at one point: a grid of one point, the centre of [p - 1, p + 1].
CgFields at_point(const Grains& g, std::span<const CgContact> contacts, CgKind kind,
                  const Vec3& p) {
  CgSettings s;
  s.kind = kind;
  s.width = 0.3;
  s.cutoff = 3.0 * s.width;
  s.grid = {p - Vec3{1, 1, 1},
            p + Vec3{1, 1, 1},
            {1, 1, 1},
            {false, false, false},
            {false, false, false}};
  return coarse_grain(g.view(), contacts, s);
}

TEST(CoarseGrain, FieldsOfMovingGrainsSatisfyTheBalancesOfMassAndMomentum) {
  const Moving m = moving_grains();
  const double dt = 1e-4, h = 1e-4;
  for (const CgKind kind : {CgKind::gaussian, CgKind::lucy})
    for (const Vec3 p : {Vec3{2.0, 2.0, 2.0}, Vec3{1.7, 2.2, 1.9}, Vec3{2.3, 1.6, 2.4}}) {
      const Grains now = at_time(m, 0.0);
      const CgFields later = at_point(at_time(m, dt), {}, kind, p);
      const CgFields earlier = at_point(at_time(m, -dt), {}, kind, p);
      const CgFields here = at_point(now, m.contacts, kind, p);
      const double rho_rate = (later.density[0] - earlier.density[0]) / (2 * dt);
      Vec3 momentum_rate;
      for (int a = 0; a < 3; ++a)
        momentum_rate[a] = (later.momentum[a] - earlier.momentum[a]) / (2 * dt);
      // Divergences by central differences: div(rho V), and div of the momentum flux
      // rho V V + sigma_k + sigma_c = sum m v v phi + sigma_c.
      double mass_divergence = 0.0;
      Vec3 flux_divergence;
      for (int b = 0; b < 3; ++b) {
        Vec3 step;
        step[b] = h;
        const CgFields plus = at_point(now, m.contacts, kind, p + step);
        const CgFields minus = at_point(now, m.contacts, kind, p - step);
        mass_divergence += (plus.momentum[b] - minus.momentum[b]) / (2 * h);
        const auto flux = [&](const CgFields& f, int a) {
          const Vec3 v{f.velocity[0], f.velocity[1], f.velocity[2]};
          return f.density[0] * v[a] * v[b] + f.kinetic_stress[3 * a + b] +
                 f.contact_stress[3 * a + b];
        };
        for (int a = 0; a < 3; ++a)
          flux_divergence[a] += (flux(plus, a) - flux(minus, a)) / (2 * h);
      }
      const double scale = std::abs(rho_rate) + std::abs(mass_divergence) + 1.0;
      EXPECT_NEAR(rho_rate + mass_divergence, 0.0, 1e-6 * scale) << to_string(kind);
      for (int a = 0; a < 3; ++a) {
        const double residual = momentum_rate[a] + flux_divergence[a] - here.wall_force[a];
        const double size = std::abs(momentum_rate[a]) + std::abs(flux_divergence[a]) + 1.0;
        EXPECT_NEAR(residual, 0.0, 1e-6 * size) << to_string(kind) << ", component " << a;
      }
    }
}

TEST(CoarseGrain, KineticStressIsTheFluctuationsAndTemperatureItsTrace) {
  // Two grains of one mass with opposite velocities at one place: V = 0, and the kinetic stress
  // at their place is m (v v + v v) phi; T = |v|^2 / 3.
  Grains g;
  g.x = {{1, 1, 1}, {1, 1, 1}};
  g.v = {{0.3, -0.4, 1.2}, {-0.3, 0.4, -1.2}};
  g.mass = {2.0, 2.0};
  g.volume = {0.1, 0.1};
  const CgFields f = at_point(g, {}, CgKind::gaussian, {1, 1, 1});
  const double phi = CgFunction(CgKind::gaussian, 0.3, 0.9, 3).at(0.0);
  EXPECT_NEAR(f.velocity[0], 0.0, 1e-15);
  EXPECT_NEAR(f.kinetic_stress[0], 2 * 2.0 * 0.09 * phi, 1e-12 * phi);
  EXPECT_NEAR(f.kinetic_stress[1], 2 * 2.0 * (0.3 * -0.4) * phi, 1e-12 * phi);
  EXPECT_NEAR(f.temperature[0], (0.09 + 0.16 + 1.44) / 3.0, 1e-12);
}

} // namespace
} // namespace yuxi::analysis

namespace yuxi::analysis {
namespace {

TEST(CoarseGrain, SumsOfPartsAddUpToTheWhole) {
  // The ranks' way: each part (its grains, its contacts, each contact once, a grain of another
  // part standing at x_a - branch) adds its sums, and the fields come from the total.
  const Moving m = moving_grains();
  CgSettings s;
  s.kind = CgKind::lucy;
  s.width = 0.3;
  s.cutoff = 0.9;
  s.grid = {{0, 0, 0}, {4, 4, 4}, {8, 8, 8}, {false, false, false}, {false, false, false}};
  const CgFields whole = coarse_grain(m.at_zero.view(), m.contacts, s);
  std::vector<double> total(cg_sums_per_point * s.grid.size(), 0.0);
  for (int part = 0; part < 2; ++part) {
    Grains g;
    std::vector<std::int64_t> index(m.at_zero.x.size(), -1);
    for (std::size_t i = 0; i < m.at_zero.x.size(); ++i) {
      if (static_cast<int>(i % 2) != part) continue;
      index[i] = static_cast<std::int64_t>(g.x.size());
      g.x.push_back(m.at_zero.x[i]);
      g.v.push_back(m.at_zero.v[i]);
      g.mass.push_back(m.at_zero.mass[i]);
      g.volume.push_back(m.at_zero.volume[i]);
    }
    // The contacts of the grains this part holds.
    std::vector<CgContact> mine;
    for (const CgContact& c : m.contacts)
      for (std::size_t i = 0; i < m.at_zero.x.size(); ++i)
        if (index[i] >= 0 && m.at_zero.x[i] == c.centre) mine.push_back(c);
    const std::vector<double> sums = coarse_grain_sums(g.view(), mine, s);
    for (std::size_t k = 0; k < total.size(); ++k) total[k] += sums[k];
  }
  const CgFields parts = coarse_grain_fields(total, s.grid);
  for (std::size_t p = 0; p < s.grid.size(); ++p) {
    EXPECT_NEAR(parts.density[p], whole.density[p], 1e-12 * (1 + whole.density[p]));
    for (int k = 0; k < 9; ++k) {
      EXPECT_NEAR(parts.stress[9 * p + k], whole.stress[9 * p + k],
                  1e-10 * (1 + std::abs(whole.stress[9 * p + k])));
      EXPECT_NEAR(parts.fabric[9 * p + k], whole.fabric[9 * p + k],
                  1e-12 * (1 + std::abs(whole.fabric[9 * p + k])));
    }
    EXPECT_NEAR(parts.coordination[p], whole.coordination[p], 1e-12);
  }
}

TEST(CoarseGrain, APartLeftOutStaysZeroAndTheOthersAreUnchanged) {
  Moving m = moving_grains();
  for (CgContact& c : m.contacts) c.elastic = 0.5, c.dissipation = 2.0, c.wall_power = 1.0;
  CgSettings s;
  s.width = 0.3;
  s.cutoff = 0.9;
  s.grid = {{0, 0, 0}, {4, 4, 4}, {8, 8, 8}, {false, false, false}, {false, false, false}};
  const std::vector<double> all = coarse_grain_sums(m.at_zero.view(), m.contacts, s);
  using detail::Sum;
  const auto same = [&](const std::vector<double>& part, std::size_t from, std::size_t count,
                        bool kept) {
    for (std::size_t p = 0; p < s.grid.size(); ++p)
      for (std::size_t k = from; k < from + count; ++k)
        ASSERT_EQ(part[cg_sums_per_point * p + k], kept ? all[cg_sums_per_point * p + k] : 0.0)
            << "sum " << k << " at point " << p;
  };
  const std::string stress[] = {"density", "stress"};
  const std::string points[] = {"elastic_energy_density"};
  const std::string fabric[] = {"coordination"};
  EXPECT_TRUE(parts_for(stress).branches);
  EXPECT_FALSE(parts_for(stress).contact_points || parts_for(stress).fabric);
  EXPECT_TRUE(parts_for(points).contact_points && !parts_for(points).branches);
  EXPECT_TRUE(parts_for(fabric).fabric && !parts_for(fabric).branches);
  for (const CgParts parts :
       {parts_for(stress), parts_for(points), parts_for(fabric), CgParts{false, false, false}}) {
    s.parts = parts;
    const std::vector<double> part = coarse_grain_sums(m.at_zero.view(), m.contacts, s);
    same(part, Sum::mass, Sum::contact_stress, true); // the grains' sums: always
    same(part, Sum::contact_stress, 9, parts.branches);
    same(part, Sum::wall_force, 3, parts.contact_points);
    same(part, Sum::elastic, 4, parts.contact_points);
    same(part, Sum::contacts, 10, parts.fabric);
  }
  // Each part holds something in the whole, so that leaving it out shows.
  for (const std::size_t k :
       {std::size_t{Sum::contact_stress}, std::size_t{Sum::elastic}, std::size_t{Sum::contacts}}) {
    double largest = 0.0;
    for (std::size_t p = 0; p < s.grid.size(); ++p)
      largest = std::max(largest, std::abs(all[cg_sums_per_point * p + k]));
    EXPECT_GT(largest, 0.0) << "sum " << k;
  }
}

TEST(CoarseGrain, FabricTraceIsVolumeFractionTimesCoordination) {
  // With grains of one volume V, tr F = sum over contacts V (phi_a + phi_b) = V n Z = nu Z.
  Moving m = moving_grains();
  for (double& v : m.at_zero.volume) v = 0.02;
  for (CgContact& c : m.contacts) c.volume = 0.02, c.volume_b = c.wall ? 0.0 : 0.02;
  for (const Vec3 p : {Vec3{2.0, 2.0, 2.0}, Vec3{1.6, 2.3, 2.1}}) {
    const CgFields f = at_point(m.at_zero, m.contacts, CgKind::gaussian, p);
    ASSERT_GT(f.coordination[0], 0.5);
    EXPECT_NEAR(f.fabric[0] + f.fabric[4] + f.fabric[8], f.volume_fraction[0] * f.coordination[0],
                1e-12 * f.volume_fraction[0] * f.coordination[0]);
  }
}

} // namespace
} // namespace yuxi::analysis

namespace yuxi::analysis {
namespace {

// Grains that sample a known density, rho(z) = rho_0 (1 + a sin(k z)) over a periodic [0, 1),
// at its exact quantiles (200,000 of them: no sampling noise), coarse-grained along z. Each
// profile is the density smoothed by its function: 1 + a T(k) sin(k z), T the function's
// Fourier transform (for bins of width h, sin(k h / 2) / (k h / 2)), to the grains' discreteness.
// T falls short of 1 by O(w^2): as w halves, the three profiles' errors fall about fourfold and
// the profiles meet (Weinhart et al. 2016 show the same for silo flow).
TEST(CoarseGrain, GaussianLucyAndBinsConvergeToTheSameProfileAsTheWidthShrinks) {
  const int n = 200000;
  const double a = 0.5, k = 2.0 * pi, mass = 1.0 / n; // rho_0 = 1 on the unit box
  Grains g;
  for (int i = 0; i < n; ++i) {
    // The quantile (i + 1/2) / n of rho: z - a (cos(k z) - 1) / k = q, by Newton's method.
    const double q = (i + 0.5) / n;
    double z = q;
    for (int it = 0; it < 50; ++it)
      z -= (z - a * (std::cos(k * z) - 1.0) / k - q) / (1.0 + a * std::sin(k * z));
    g.x.push_back({0.5, 0.5, z});
    g.v.push_back({0.0, 0.0, 0.0});
    g.mass.push_back(mass);
    g.volume.push_back(0.0);
  }
  const std::array<CgKind, 3> kinds{CgKind::gaussian, CgKind::lucy, CgKind::bins};
  std::array<std::vector<double>, 3> shortfall; // 1 - T at each width
  std::array<std::vector<double>, 3> finest;    // the profiles at the smallest width
  for (const int points : {8, 16, 32, 64}) {
    const double w = 1.0 / points;
    for (std::size_t m = 0; m < kinds.size(); ++m) {
      CgSettings s;
      s.kind = kinds[m];
      s.width = w;
      s.cutoff = 3.0 * w;
      // Points w / 2 apart (the bins' cells as wide).
      s.grid = {{0, 0, 0}, {1, 1, 1}, {1, 1, 2 * points}, {true, true, false}, {true, true, true}};
      double transform = 0.0, tolerance = 1e-6;
      if (s.kind == CgKind::bins) {
        const double half = 0.5 * k * s.grid.spacing(2);
        transform = std::sin(half) / half;
        tolerance = 2.0 / (n * s.grid.spacing(2)); // a grain more or less in a cell
      } else {
        const CgFunction phi(s.kind, w, s.cutoff, 1);
        transform = simpson([&](double u) { return phi.at(u * u) * std::cos(k * u); }, -s.cutoff,
                            s.cutoff, 20000);
      }
      const CgFields f = coarse_grain(g.view(), {}, s);
      for (int p = 0; p < s.grid.n[2]; ++p)
        EXPECT_NEAR(f.density[static_cast<std::size_t>(p)],
                    1.0 + a * transform * std::sin(k * s.grid.coordinate(2, p)), tolerance)
            << to_string(s.kind) << ", w = 1/" << points << ", point " << p;
      shortfall[m].push_back(1.0 - transform);
      if (points == 64) finest[m] = f.density;
    }
  }
  for (std::size_t m = 0; m < kinds.size(); ++m)
    for (std::size_t e = 1; e < shortfall[m].size(); ++e)
      EXPECT_GT(shortfall[m][e - 1] / shortfall[m][e], 3.5) << to_string(kinds[m]);
  // At w = 1/64 the three profiles agree within 1 % of the variation's amplitude.
  for (std::size_t p = 0; p < finest[0].size(); ++p) {
    EXPECT_NEAR(finest[0][p], finest[1][p], 0.01 * a) << p;
    EXPECT_NEAR(finest[0][p], finest[2][p], 0.01 * a) << p;
  }
}

TEST(CoarseGrain, AnAverageCountsOnlyWhatLiesWithinItsSpan) {
  // A profile along z averaged over x in [0, 2] and y in [0, 2] (bounded): a grain at x = 5
  // does not count, and a contact whose branch lies half inside counts half.
  Grains g;
  g.x = {{1.0, 1.0, 1.0}, {5.0, 1.0, 1.0}};
  g.v = {{0, 0, 0}, {0, 0, 0}};
  g.mass = {1.0, 1.0};
  g.volume = {0.1, 0.1};
  for (const CgKind kind : {CgKind::gaussian, CgKind::bins}) {
    CgSettings s;
    s.kind = kind;
    s.width = 0.3;
    s.cutoff = 0.9;
    s.grid = {{0, 0, -4}, {2, 2, 6}, {1, 1, 100}, {true, true, false}, {false, false, false}};
    const std::vector<CgContact> contacts{
        {{2.5, 1.0, 1.0}, 0.1, false, 0.1, {1.0, 0, 0}, {1.0, 0, 0}, {2.0, 1.0, 1.0}, 0.0}};
    const CgFields f = coarse_grain(g.view(), contacts, s);
    double mass = 0.0, stress = 0.0;
    for (std::size_t p = 0; p < s.grid.size(); ++p) {
      mass += f.density[p] * s.grid.cell_volume();
      stress += f.contact_stress[9 * p] * s.grid.cell_volume();
    }
    // The grain at x = 1 only, and f b over the half within x <= 2: to round-off with bins, to
    // the grid's sum of the Gaussian (its kink at the cutoff, sampled at w / 3) otherwise.
    const double tolerance = kind == CgKind::bins ? 1e-12 : 1e-3;
    EXPECT_NEAR(mass, 1.0, tolerance) << to_string(kind);
    EXPECT_NEAR(stress, 0.5, tolerance) << to_string(kind);
  }
}

} // namespace
} // namespace yuxi::analysis

namespace yuxi::analysis {
namespace {

TEST(CoarseGrain, TheSceneNamesTheFieldsThatTheAnalysisMakes) {
  // A [[coarse_grain]] table's `fields` are checked against the scene's list; the files and
  // Python take the fields by the analysis's names: the two lists are one.
  const CgFields f;
  std::vector<std::string> made;
  for (const CgNamedField& n : named_fields(f)) made.emplace_back(n.name);
  EXPECT_EQ(made, CoarseGrainSpec::field_names());
}

} // namespace
} // namespace yuxi::analysis
