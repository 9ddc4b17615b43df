// The analyses behind the fish-basin figures, on inputs whose answers are known in closed form:
// a surface of known shape, sums that must equal totals, rigid-body velocity fields, and samples
// of a Pareto law with a known exponent and energy fraction.
#include "analysis/analysis_csv.hpp"
#include "analysis/column_sum.hpp"
#include "analysis/free_surface.hpp"
#include "analysis/grain_energy.hpp"
#include "analysis/power_law.hpp"
#include "analysis/section_energies.hpp"
#include "analysis/velocity_section.hpp"
#include "analysis/xy_grid.hpp"
#include "core/random.hpp"
#include "temp_folder.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace yuxi::analysis {
namespace {

namespace fs = std::filesystem;

using test::temp_dir;

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<double> numbers_of(const std::string& line) {
  std::vector<double> v;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) v.push_back(std::stod(cell));
  return v;
}

// Pareto law p(E) = (a - 1) E_m^(a-1) E^-a for E >= E_m, by inverting its distribution.
double pareto(double u, double a, double e_m) {
  return e_m * std::pow(1.0 - u, -1.0 / (a - 1.0));
}

std::vector<double> pareto_sample(std::uint64_t seed, std::size_t n, double a, double e_m) {
  Random rng(seed);
  std::vector<double> e(n);
  for (auto& v : e) v = pareto(rng.uniform(), a, e_m);
  return e;
}

// ---------------------------------------------------------------------------------------------
// Grid and CSV

TEST(XYGrid, ColumnsAreHalfOpenAndPointsOutsideAreInNone) {
  const XYGrid g({0, 0, 0}, {4, 2, 0}, 4, 2);
  EXPECT_DOUBLE_EQ(g.dx(), 1.0);
  EXPECT_DOUBLE_EQ(g.dy(), 1.0);
  EXPECT_EQ(g.cell_of({0, 0, 5}), 0u);
  EXPECT_EQ(g.cell_of({1.0, 0.5, 0}), 1u); // on a face: the upper column
  EXPECT_EQ(g.cell_of({3.999, 1.999, 0}), g.index(3, 1));
  EXPECT_FALSE(g.cell_of({4.0, 0.5, 0}));
  EXPECT_FALSE(g.cell_of({-1e-12, 0.5, 0}));
  EXPECT_FALSE(g.cell_of({std::nan(""), 0.5, 0}));
  EXPECT_DOUBLE_EQ(g.x_center(3), 3.5);
  EXPECT_DOUBLE_EQ(g.y_center(1), 1.5);
  EXPECT_THROW(XYGrid({0, 0, 0}, {1, 1, 0}, 0, 1), std::invalid_argument);
  EXPECT_THROW(XYGrid({0, 0, 0}, {0, 1, 0}, 1, 1), std::invalid_argument);
}

TEST(AnalysisCsv, NumbersReadBackExactlyAndTimesNameFiles) {
  for (const double v : {0.1, 1.0 / 3.0, -2.5e-300, 1e300, 12345.678})
    EXPECT_EQ(std::stod(csv_number(v)), v);
  EXPECT_EQ(csv_number(std::nan("")), "nan");
  EXPECT_EQ(csv_number(-std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(timed_file_name("surface", 10.25), "surface_t10.25.csv");
  EXPECT_EQ(timed_file_name("velocity", 10.5), "velocity_t10.50.csv");
  EXPECT_EQ(timed_file_name("elastic_map", 10.0625, 4), "elastic_map_t10.0625.csv");
}

TEST(AnalysisCsv, GridIsWrittenLongWithXFastest) {
  const auto dir = temp_dir("grid_csv");
  const XYGrid g({0, 0, 0}, {3, 2, 0}, 3, 2);
  std::vector<double> v(g.size());
  for (std::size_t c = 0; c < v.size(); ++c) v[c] = 10.0 * static_cast<double>(c);
  v[4] = std::nan("");
  const GridColumn col{"value", v};
  write_grid_csv(dir / "sub" / "g.csv", g, std::span<const GridColumn>(&col, 1));
  const auto lines = lines_of(dir / "sub" / "g.csv");
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[0], "x,y,value");
  EXPECT_EQ(lines[1], "0.5,0.5,0");
  EXPECT_EQ(lines[2], "1.5,0.5,10");
  EXPECT_EQ(lines[4], "0.5,1.5,30");
  EXPECT_EQ(lines[5], "1.5,1.5,nan");
  const std::vector<double> short_column(2);
  const GridColumn bad{"value", short_column};
  EXPECT_THROW(write_grid_csv(dir / "bad.csv", g, std::span<const GridColumn>(&bad, 1)),
               std::invalid_argument);
  CsvWriter csv(dir / "w.csv", {"a", "b"});
  EXPECT_THROW(csv.row({1.0}), std::invalid_argument);
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------------
// Free surface

TEST(FreeSurface, SmallBedHasItsHighestTopsAndEmptyColumnsAreNaN) {
  const XYGrid g({0, 0, 0}, {2, 2, 0}, 2, 2);
  const std::vector<Vec3> p{{0.5, 0.5, 1.0}, {0.7, 0.2, 2.0}, {1.5, 0.5, 0.0}, {2.0, 0.5, 100.0}};
  const std::vector<double> r{0.5, 0.25, 1.0, 1.0};
  const GridField s = free_surface(g, p, r);
  EXPECT_DOUBLE_EQ(s.at(0, 0), 2.25);
  EXPECT_DOUBLE_EQ(s.at(1, 0), 1.0);
  EXPECT_TRUE(std::isnan(s.at(0, 1)));
  EXPECT_TRUE(std::isnan(s.at(1, 1)));
  EXPECT_THROW(free_surface(g, p, std::vector<double>{1.0}), std::invalid_argument);
}

TEST(FreeSurface, RecoversAParaboloidWithinTheGrainSize) {
  // Grains under the paraboloid z = h0 + c |x - x_c|^2: four per column touch it (top on the
  // surface), twenty lie buried; one corner column is left empty; grains off the grid fly high.
  const double h0 = 20.0, c = 0.005, xc = 30.0, yc = 30.0;
  const auto f = [&](double x, double y) {
    return h0 + c * ((x - xc) * (x - xc) + (y - yc) * (y - yc));
  };
  const XYGrid g({0, 0, 0}, {60, 60, 0}, 20, 20);
  Random rng(11);
  std::vector<Vec3> p;
  std::vector<double> r;
  for (std::size_t j = 0; j < g.ny(); ++j)
    for (std::size_t i = 0; i < g.nx(); ++i) {
      if (i == 0 && j == 0) continue;
      for (int k = 0; k < 24; ++k) {
        const double x = g.x_center(i) + g.dx() * rng.uniform(-0.5, 0.5);
        const double y = g.y_center(j) + g.dy() * rng.uniform(-0.5, 0.5);
        const double radius = 1.0 + 0.1 * rng.normal();
        const double depth = k < 4 ? 0.0 : rng.uniform(0.5, 10.0);
        p.push_back({x, y, f(x, y) - radius - depth});
        r.push_back(radius);
      }
    }
  p.push_back({-1.0, 30.0, 500.0});
  r.push_back(1.0);
  p.push_back({30.0, 61.0, 500.0});
  r.push_back(1.0);

  const GridField s = free_surface(g, p, r);
  EXPECT_TRUE(std::isnan(s.at(0, 0)));
  for (std::size_t j = 0; j < g.ny(); ++j)
    for (std::size_t i = 0; i < g.nx(); ++i) {
      if (i == 0 && j == 0) continue;
      const double x = g.x_center(i), y = g.y_center(j);
      // The paraboloid over the column lies between its values at the nearest and the farthest
      // point from the axis; the map must be one of those heights (a top on the surface).
      const double hx = g.dx() / 2, hy = g.dy() / 2;
      const double near_x = std::clamp(xc, x - hx, x + hx), near_y = std::clamp(yc, y - hy, y + hy);
      const double far_x = std::abs(x - hx - xc) > std::abs(x + hx - xc) ? x - hx : x + hx;
      const double far_y = std::abs(y - hy - yc) > std::abs(y + hy - yc) ? y - hy : y + hy;
      EXPECT_GE(s.at(i, j), f(near_x, near_y) - 1e-9) << i << "," << j;
      EXPECT_LE(s.at(i, j), f(far_x, far_y) + 1e-9) << i << "," << j;
      EXPECT_NEAR(s.at(i, j), f(x, y), 1.0) << i << "," << j; // within a grain radius
    }
}

// ---------------------------------------------------------------------------------------------
// Column sums and slabs

TEST(ColumnSum, ColumnsAddUpToTheTotalOfTheGrainsOnTheGrid) {
  const XYGrid g({-10, -10, 0}, {10, 10, 0}, 7, 5);
  Random rng(3);
  std::vector<Vec3> p(5000);
  std::vector<double> e(p.size());
  double inside = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    p[k] = {rng.uniform(-12, 12), rng.uniform(-12, 12), rng.uniform(0, 40)};
    e[k] = rng.uniform(0, 3);
    if (std::abs(p[k].x) < 10 && std::abs(p[k].y) < 10) inside += e[k];
  }
  const GridField s = column_sum(g, p, e);
  double total = 0.0;
  for (const double v : s.values) total += v;
  EXPECT_NEAR(total, inside, 1e-9 * inside);

  // One column holding three grains at different heights and one next to it.
  const XYGrid g2({0, 0, 0}, {2, 1, 0}, 2, 1);
  const std::vector<Vec3> q{{0.5, 0.5, 1}, {0.5, 0.5, 50}, {0.1, 0.9, -3}, {1.5, 0.5, 2}};
  const GridField s2 = column_sum(g2, q, std::vector<double>{1, 2, 3, 7});
  EXPECT_DOUBLE_EQ(s2.at(0, 0), 6.0);
  EXPECT_DOUBLE_EQ(s2.at(1, 0), 7.0);
}

// Fig. 9 by coarse-graining: with bins each cell holds the paper's time-averaged cell totals
// over the cell's volume; with a Gaussian the densities hold the grains' count and energies.
TEST(SectionEnergies, BinsAreTheCellTotalsOverTheCellVolumeAndAGaussianHoldsTheTotals) {
  const XYGrid g({0, 0, 0}, {2, 1, 0}, 2, 1);
  const std::vector<Vec3> p{{0.5, 0.5, 2.0}, {0.5, 0.5, 3.9}, {0.5, 0.5, 4.5}, {0.5, 0.5, 1.99}};
  const std::vector<Vec3> p2{{0.5, 0.5, 2.5}, {1.5, 0.5, 3.0}};
  const std::vector<double> e{1.0, 3.0, 100.0, 1000.0}, e2{8.0, 6.0};
  const std::vector<double> heights{2.0, 4.0, 4.0, 8.0};
  SectionEnergies bins(g, heights, 0.0);
  bins.add(p, std::vector<double>{5, 5, 5, 5}, e);
  bins.add(p2, std::vector<double>{1, 1}, e2);
  EXPECT_EQ(bins.snapshots(), 2u);
  for (std::size_t section = 0; section < 2; ++section) {
    // The paper's cells: each cell's grains (z0 <= z < z1), their count and energies, summed
    // and divided by the two snapshots.
    const double z0 = heights[2 * section], z1 = heights[2 * section + 1];
    std::vector<double> count(g.size(), 0.0), kinetic(g.size(), 0.0), elastic(g.size(), 0.0);
    const auto add = [&](const std::vector<Vec3>& x, const std::vector<double>& k,
                         const std::vector<double>& el) {
      for (std::size_t i = 0; i < x.size(); ++i)
        if (const auto cell = g.cell_of(x[i]); cell && x[i].z >= z0 && x[i].z < z1)
          count[*cell] += 0.5, kinetic[*cell] += 0.5 * k[i], elastic[*cell] += 0.5 * el[i];
    };
    add(p, {5, 5, 5, 5}, e);
    add(p2, {1, 1}, e2);
    const double volume = 1.0 * 1.0 * (z1 - z0);
    const std::vector<double> m = bins.means(section);
    for (std::size_t c = 0; c < g.size(); ++c) {
      EXPECT_DOUBLE_EQ(m[3 * c] * volume, count[c]) << section << " " << c;
      EXPECT_DOUBLE_EQ(m[3 * c + 1] * volume, kinetic[c]);
      EXPECT_DOUBLE_EQ(m[3 * c + 2] * volume, elastic[c]);
    }
  }
  const auto dir = temp_dir("sections");
  bins.write_csv(dir / "period_sections.csv");
  const auto lines = lines_of(dir / "period_sections.csv");
  ASSERT_EQ(lines.size(), 1u + 2 * g.size());
  EXPECT_EQ(lines[0], "section,z0,z1,x,y,number_density,kinetic_energy_density,"
                      "elastic_energy_density");
  EXPECT_EQ(numbers_of(lines[1]), (std::vector<double>{0, 2, 4, 0.5, 0.5, 0.75, 2.75, 3.0}));
  EXPECT_EQ(numbers_of(lines[3]), (std::vector<double>{1, 4, 8, 0.5, 0.5, 0.125, 0.625, 12.5}));
  fs::remove_all(dir);
  EXPECT_THROW(SectionEnergies(g, std::vector<double>{4.0, 4.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(SectionEnergies(g, std::vector<double>{1.0}, 0.0), std::invalid_argument);
  EXPECT_THROW(SectionEnergies(g, heights, -1.0), std::invalid_argument);

  // A Gaussian of width 1 sampled every 0.5 over a grid that holds it: the densities integrate
  // to the slab's grains and their energies.
  const XYGrid wide({0, 0, 0}, {20, 20, 0}, 40, 40);
  SectionEnergies smooth(wide, heights, 1.0);
  const std::vector<Vec3> inside{{9.3, 10.1, 2.5}, {10.7, 8.2, 3.5}, {11.0, 11.0, 9.0}};
  smooth.add(inside, std::vector<double>{2.0, 3.0, 4.0}, std::vector<double>{0.5, 0.25, 7.0});
  const std::vector<double> m = smooth.means(0);
  double totals[3] = {0, 0, 0};
  for (std::size_t c = 0; c < wide.size(); ++c)
    for (int k = 0; k < 3; ++k) totals[k] += m[3 * c + k] * 0.5 * 0.5 * 2.0;
  EXPECT_NEAR(totals[0], 2.0, 2e-3);
  EXPECT_NEAR(totals[1], 5.0, 5e-3);
  EXPECT_NEAR(totals[2], 0.75, 1e-3);
}

// ---------------------------------------------------------------------------------------------
// Velocity section

TEST(VelocitySection, SelectsTheSliceAndRecoversItsCoordinates) {
  const Vec3 axis{40, 30, 0};
  const double a = 0.7;
  const Vec3 e{std::cos(a), std::sin(a), 0}, n{-std::sin(a), std::cos(a), 0};
  std::vector<Vec3> p, v;
  std::vector<double> s_of, z_of;
  for (const double d : {-2.0, -1.4, 0.0, 1.4, 2.0})
    for (const double s : {-20.0, -3.0, 0.0, 5.0, 19.0}) {
      const double z = 10.0 + s / 4;
      p.push_back(axis + s * e + d * n + Vec3{0, 0, z});
      v.push_back({0, 0, 0});
      s_of.push_back(s);
      z_of.push_back(z);
    }
  const VelocitySection sec = velocity_section(p, v, axis, a, 1.5);
  ASSERT_EQ(sec.points.size(), 15u); // d = -1.4, 0, 1.4
  for (const auto& q : sec.points) {
    EXPECT_NEAR(q.s, s_of[q.index], 1e-12);
    EXPECT_DOUBLE_EQ(q.z, z_of[q.index]);
    EXPECT_LE(std::abs(dot(p[q.index] - axis - Vec3{0, 0, p[q.index].z}, n)), 1.5);
  }
  EXPECT_THROW(velocity_section(p, v, axis, a, -1.0), std::invalid_argument);
}

TEST(VelocitySection, RigidRotationsHaveTheirKnownInPlaneVelocities) {
  // Grains in a cylinder of radius 30 around (40, 30); a slice at azimuth 2.2 rad.
  const Vec3 axis{40, 30, 0};
  const double a = 2.2, omega = 3.0, z0 = 12.0;
  const Vec3 n{-std::sin(a), std::cos(a), 0};
  Random rng(5);
  std::vector<Vec3> p(4000);
  for (auto& q : p) {
    const double rho = 30 * std::sqrt(rng.uniform()), phi = rng.uniform(0, 2 * pi);
    q = {axis.x + rho * std::cos(phi), axis.y + rho * std::sin(phi), rng.uniform(0, 40)};
  }
  // Spin about the vertical axis: velocities are normal to the plane, vn = omega s.
  std::vector<Vec3> spin(p.size()), tumble(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    spin[k] = cross(Vec3{0, 0, omega}, p[k] - Vec3{axis.x, axis.y, p[k].z});
    // Tumbling about the plane's normal through (axis, z0): vs = omega (z - z0), vz = -omega s.
    tumble[k] = cross(omega * n, p[k] - Vec3{axis.x, axis.y, z0});
  }
  const VelocitySection by_spin = velocity_section(p, spin, axis, a, 1.0);
  const VelocitySection by_tumble = velocity_section(p, tumble, axis, a, 1.0);
  ASSERT_GT(by_spin.points.size(), 50u);
  ASSERT_EQ(by_spin.points.size(), by_tumble.points.size());
  for (const auto& q : by_spin.points) {
    const double d = dot(p[q.index] - axis, n); // distance from the plane
    EXPECT_NEAR(q.vs, -omega * d, 1e-9);        // the part of the spin along e
    EXPECT_NEAR(q.vz, 0.0, 1e-12);
    EXPECT_NEAR(q.vn, omega * q.s, 1e-9);
  }
  for (const auto& q : by_tumble.points) {
    EXPECT_NEAR(q.vs, omega * (q.z - z0), 1e-9);
    EXPECT_NEAR(q.vz, -omega * q.s, 1e-9);
    EXPECT_NEAR(q.vn, 0.0, 1e-9);
  }
}

// ---------------------------------------------------------------------------------------------
// Per-grain energies

TEST(GrainEnergy, ContactsAreSharedHalfAndHalfAndWallsKeepNone) {
  const std::vector<ContactEnergy> c{{0, 1, 2.0}, {1, wall_partner, 4.0}, {wall_partner, 2, 6.0}};
  const auto e = grain_elastic_energy(4, c);
  EXPECT_EQ(e, (std::vector<double>{1.0, 3.0, 3.0, 0.0}));
  const std::vector<ContactEnergy> bad{{0, 4, 1.0}};
  EXPECT_THROW(grain_elastic_energy(4, bad), std::out_of_range);

  // Many contacts: the grains hold all of the grain-grain energy and half the grain-wall one.
  Random rng(9);
  const std::size_t n = 300;
  std::vector<ContactEnergy> many(2000);
  double expected = 0.0;
  for (auto& m : many) {
    m.i = static_cast<std::size_t>(rng.uniform() * n);
    m.j = rng.uniform() < 0.2 ? wall_partner : static_cast<std::size_t>(rng.uniform() * n);
    m.energy = rng.uniform(0, 1e-3);
    expected += m.j == wall_partner ? 0.5 * m.energy : m.energy;
  }
  const auto per_grain = grain_elastic_energy(n, many);
  double sum = 0.0;
  for (const double v : per_grain) sum += v;
  EXPECT_NEAR(sum, expected, 1e-12 * expected);
}

TEST(GrainEnergy, KineticIsTranslationalPlusRotational) {
  const std::vector<double> m{2.0, 1.0}, J{0.4, 0.1};
  const std::vector<Vec3> v{{1, 2, 2}, {0, 0, 0}}, w{{0, 0, 5}, {3, 4, 0}};
  EXPECT_EQ(grain_translational_energy(m, v), (std::vector<double>{9.0, 0.0}));
  EXPECT_EQ(grain_rotational_energy(J, w), (std::vector<double>{5.0, 1.25}));
  EXPECT_EQ(grain_kinetic_energy(m, v, J, w), (std::vector<double>{14.0, 1.25}));
  EXPECT_THROW(grain_kinetic_energy(m, v, std::vector<double>{1.0}, w), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------
// Densities and power laws

TEST(PowerLaw, BinsAreLogarithmicAndTheDensityIsNormalisedToAllSamples) {
  LogHistogram h(1e-3, 1e4, 5);
  ASSERT_EQ(h.bins(), 35u);
  EXPECT_NEAR(h.edges().back(), 1e4, 1e-9);
  EXPECT_NEAR(h.edges()[15], 1.0, 1e-14);
  // A value on an edge is in the bin above it.
  h.add(h.edges()[15]);
  h.add(std::nextafter(h.edges()[15], 0.0));
  h.add(0.0); // a grain without contacts: counted in N, in no bin
  h.add(2e4);
  h.add(std::nan(""));
  const Density d = h.density();
  ASSERT_EQ(d.bins.size(), 2u);
  EXPECT_EQ(d.bins[0].e_hi, d.bins[1].e_lo);
  EXPECT_EQ(d.bins[0].count, 1u);
  EXPECT_EQ(d.samples, 4u);
  EXPECT_EQ(d.below, 1u);
  EXPECT_EQ(d.above, 1u);
  EXPECT_EQ(d.non_finite, 1u);
  EXPECT_NEAR(d.bins[1].e_center, std::pow(10.0, 0.1), 1e-12);
  EXPECT_DOUBLE_EQ(d.bins[1].density, 1.0 / (4.0 * (d.bins[1].e_hi - d.bins[1].e_lo)));

  // Uniform sample on [0, 2): the densities integrate to the fraction inside [1e-3, 1e4).
  Random rng(1);
  std::vector<double> u(100000);
  for (auto& x : u) x = 2.0 * rng.uniform();
  const Density du = log_density(u, 1e-3, 1e4, 5);
  double integral = 0.0;
  for (const auto& b : du.bins) integral += b.density * (b.e_hi - b.e_lo);
  EXPECT_NEAR(integral, 1.0 - static_cast<double>(du.below) / 100000.0, 1e-12);
  for (const auto& b : du.bins) // bins inside [0.1, 2) hold the uniform density 1/2
    if (b.e_lo >= 0.1 && b.e_hi <= 2.0) {
      EXPECT_NEAR(b.density, 0.5, 0.04) << b.e_lo;
    }
  EXPECT_THROW(LogHistogram(0.0, 1.0, 5), std::invalid_argument);
  EXPECT_THROW(LogHistogram(1.0, 10.0, 0), std::invalid_argument);
}

TEST(PowerLaw, LeastSquaresMatchesHandComputedValues) {
  // Three points (x, y) = (0, 0), (1, 1), (2, 3): slope 3/2, intercept -1/6, residuals
  // 1/6, -1/3, 1/6, standard error sqrt((1/6) / 1 / 2).
  Density d;
  d.total_energy = 10.0;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0, 0}, {1, 1}, {2, 3}}) {
    const double e = std::pow(10.0, x);
    d.bins.push_back({e / 1.1, e * 1.1, e, 1, std::pow(10.0, y), 2.0});
  }
  const PowerLawFit f = fit_power_law(d, 0.5, 200.0);
  EXPECT_EQ(f.bins, 3u);
  EXPECT_NEAR(f.slope, 1.5, 1e-12);
  EXPECT_NEAR(f.intercept, -1.0 / 6.0, 1e-12);
  EXPECT_NEAR(f.slope_error, std::sqrt(1.0 / 12.0), 1e-12);
  EXPECT_NEAR(f.energy_fraction, 0.6, 1e-15);
  EXPECT_DOUBLE_EQ(f.e_lo_used, 1.0 / 1.1);
  EXPECT_DOUBLE_EQ(f.e_hi_used, 110.0);
  // The range picks bins by their centres; two points give no error, one no slope.
  const PowerLawFit two = fit_power_law(d, 0.5, 50.0);
  EXPECT_EQ(two.bins, 2u);
  EXPECT_NEAR(two.slope, 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(two.slope_error));
  EXPECT_TRUE(std::isnan(fit_power_law(d, 5.0, 50.0).slope));
  EXPECT_THROW(fit_power_law(d, 2.0, 1.0), std::invalid_argument);
}

TEST(PowerLaw, ExactPowerLawBinsGiveTheExponent) {
  // Bin-averaged densities of p(E) = (a-1) E_m^(a-1) E^-a: on logarithmic bins of ratio q they
  // are exactly proportional to e_center^-a, so the fit returns -a with no scatter.
  const double a = 2.691, e_m = 0.01, q = std::pow(10.0, 0.1);
  Density d;
  for (int k = 0; k < 40; ++k) {
    const double lo = e_m * std::pow(q, k), hi = lo * q;
    const double p = std::pow(e_m / lo, a - 1) - std::pow(e_m / hi, a - 1); // probability
    d.bins.push_back({lo, hi, std::sqrt(lo * hi), 1, p / (hi - lo), 1.0});
  }
  const PowerLawFit f = fit_power_law(d, 0.2, 2.0);
  EXPECT_EQ(f.bins, 10u);
  EXPECT_NEAR(f.slope, -a, 1e-10);
  EXPECT_LT(f.slope_error, 1e-10);
}

TEST(PowerLaw, ParetoSampleGivesItsExponentWithinTheStandardError) {
  const double a = 2.7, e_m = 0.1;
  {
    const auto e = pareto_sample(2008, 1000000, a, e_m);
    const PowerLawFit f = fit_power_law(log_density(e, 1e-3, 1e4, 10), 0.2, 2.0);
    EXPECT_EQ(f.bins, 10u);
    EXPECT_GT(f.slope_error, 0.0);
    EXPECT_LT(f.slope_error, 0.02);
    EXPECT_LE(std::abs(f.slope + a), f.slope_error) << f.slope << " +- " << f.slope_error;
  }
  // Over 20 seeds. The error is estimated from 10 residuals, so |slope + a| / error follows a
  // t law with 8 degrees of freedom: beyond 3 errors in 1.7 % of samples, beyond 1 in 35 %.
  // The slopes are unbiased, and the errors match the scatter of the slopes between samples.
  std::vector<double> slopes, errors;
  int beyond_1 = 0, beyond_3 = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto e = pareto_sample(seed, 200000, a, e_m);
    const PowerLawFit f = fit_power_law(log_density(e, 1e-3, 1e4, 10), 0.2, 2.0);
    const double t = std::abs(f.slope + a) / f.slope_error;
    if (seed <= 5) {
      EXPECT_LE(t, 3.0) << "seed " << seed;
    }
    beyond_1 += t > 1.0;
    beyond_3 += t > 3.0;
    slopes.push_back(f.slope);
    errors.push_back(f.slope_error);
  }
  EXPECT_LE(beyond_3, 1);
  EXPECT_LE(beyond_1, 14);
  double mean = 0.0, var = 0.0, rms_error = 0.0;
  for (const double s : slopes) mean += s / 20;
  for (const double s : slopes) var += (s - mean) * (s - mean) / 19;
  for (const double s : errors) rms_error += s * s / 20;
  EXPECT_LE(std::abs(mean + a), 3 * std::sqrt(var / 20));
  const double ratio = std::sqrt(var) / std::sqrt(rms_error);
  EXPECT_GT(ratio, 0.5);
  EXPECT_LT(ratio, 2.0);
}

TEST(PowerLaw, EnergyFractionOfKnownDistributions) {
  // Quantiles of the Pareto law: the energy in [lo, hi] over all is
  // (lo/E_m)^(2-a) - (hi/E_m)^(2-a) (about 49 % for a = 2.7, E_m = 0.1, [0.2, 2]).
  const double a = 2.7, e_m = 0.1;
  const std::size_t n = 1000000;
  std::vector<double> e(n);
  for (std::size_t k = 0; k < n; ++k)
    e[k] = pareto((static_cast<double>(k) + 0.5) / static_cast<double>(n), a, e_m);
  const auto analytic = [&](double lo, double hi) {
    return std::pow(lo / e_m, 2 - a) - std::pow(hi / e_m, 2 - a);
  };
  EXPECT_NEAR(energy_fraction(e, 0.2, 2.0), analytic(0.2, 2.0), 0.005);
  EXPECT_NEAR(energy_fraction(e, 10.0, 1e4), analytic(10.0, 1e4), 0.005);
  // The fit's fraction is that of the bins it used.
  const PowerLawFit f = fit_power_law(log_density(e, 1e-3, 1e4, 10), 0.2, 2.0);
  EXPECT_NEAR(f.e_lo_used, 0.2, 0.01);
  EXPECT_NEAR(f.e_hi_used, 2.0, 0.01);
  EXPECT_NEAR(f.energy_fraction, analytic(f.e_lo_used, f.e_hi_used), 0.005);
  // Uniform on [0, 1]: three quarters of the energy lies in [1/2, 1].
  std::vector<double> u(n);
  for (std::size_t k = 0; k < n; ++k)
    u[k] = (static_cast<double>(k) + 0.5) / static_cast<double>(n);
  EXPECT_NEAR(energy_fraction(u, 0.5, 1.0), 0.75, 1e-6);
  EXPECT_TRUE(std::isnan(energy_fraction(std::vector<double>{0.0, 0.0}, 0.5, 1.0)));
}

TEST(PowerLaw, DensityAndFitsAreWrittenWithTheirHeaders) {
  const auto dir = temp_dir("pdf_csv");
  const auto e = pareto_sample(4, 10000, 2.5, 0.1);
  const Density d = log_density(e, 1e-3, 1e4, 10);
  write_density_csv(dir / "pdf_kinetic.csv", d);
  const auto lines = lines_of(dir / "pdf_kinetic.csv");
  ASSERT_EQ(lines.size(), 1 + d.bins.size());
  EXPECT_EQ(lines[0], "e_lo,e_hi,e_center,count,density,energy");
  const auto first = numbers_of(lines[1]);
  EXPECT_EQ(first[3], static_cast<double>(d.bins[0].count));
  EXPECT_EQ(first[4], d.bins[0].density);

  const std::vector<NamedFit> fits{{"kinetic", "A", 0.2, 2.0, fit_power_law(d, 0.2, 2.0)},
                                   {"total", "B", 10, 1e4, fit_power_law(d, 1e3, 1e4)}};
  write_fits_csv(dir / "fits.csv", fits);
  const auto fl = lines_of(dir / "fits.csv");
  ASSERT_EQ(fl.size(), 3u);
  EXPECT_EQ(fl[0], "quantity,range,e_lo,e_hi,slope,intercept,slope_error,bins,energy_fraction,"
                   "e_lo_used,e_hi_used");
  EXPECT_EQ(fl[1].rfind("kinetic,A,0.2,2,", 0), 0u);
  fs::remove_all(dir);
}

} // namespace
} // namespace yuxi::analysis
