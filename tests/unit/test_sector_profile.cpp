// Profiles of an x-y field by sector of the excitation mode, and the .npy records of the
// per-grain samples, on fields whose answers are known in closed form.
#include "analysis/sector_profile.hpp"
#include "core/units.hpp"
#include "io/npy_records.hpp"
#include "temp_folder.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <stdexcept>

namespace yuxi::analysis {
namespace {

// A grid of 1 x 1 columns over [-50, 50]^2 about the axis at the origin.
XYGrid square_grid() {
  return XYGrid({-50, -50, 0}, {50, 50, 0}, 100, 100);
}

// The field f(r, alpha) at every column centre.
template <class F> GridField field_of(F f) {
  GridField g{square_grid(), {}};
  for (std::size_t j = 0; j < g.grid.ny(); ++j)
    for (std::size_t i = 0; i < g.grid.nx(); ++i) {
      const double x = g.grid.x_center(i), y = g.grid.y_center(j);
      g.values.push_back(f(std::hypot(x, y), std::atan2(y, x)));
    }
  return g;
}

ModeSectors sectors(int m, double half_width_degrees = 5.0) {
  return {{0, 0, 0}, m, half_width_degrees * pi / 180.0, 40.0};
}

TEST(SectorProfile, AntinodesAndNodesAlternateEveryQuarterWavelength) {
  const ModeSectors s = sectors(2);
  // m = 2: antinodes at 0, 90, 180, 270 degrees; nodes at 45, 135, 225, 315.
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(sector_azimuth(s, SectorKind::antinode, k), k * pi / 2, 1e-15);
    EXPECT_NEAR(sector_azimuth(s, SectorKind::node, k), (k + 0.5) * pi / 2, 1e-15);
  }
  EXPECT_EQ(sector_of(s, SectorKind::antinode, {20, 0.5, 0}), 0);
  EXPECT_EQ(sector_of(s, SectorKind::antinode, {-0.5, -20, 0}), 3);
  EXPECT_EQ(sector_of(s, SectorKind::antinode, {20, 20, 0}), -1);
  EXPECT_EQ(sector_of(s, SectorKind::node, {20, 20, 0}), 0);
  EXPECT_EQ(sector_of(s, SectorKind::node, {20, -20, 0}), 3);
  EXPECT_EQ(sector_of(s, SectorKind::antinode, {41, 0, 0}), -1) << "beyond r_max";
}

TEST(SectorProfile, ProfileOfCosModeFieldIsOneAtAntinodesAndZeroAtNodes) {
  // f = |cos(m alpha)| r: along the antinode wedges (5 degrees) f/r >= cos(10 degrees), along
  // the nodes f/r <= sin(10 degrees); the mean of each radial bin lies within those bounds.
  for (int m : {2, 3}) {
    const GridField f = field_of([m](double r, double a) { return std::abs(std::cos(m * a)) * r; });
    const auto anti = radial_profile(f, sectors(m), SectorKind::antinode, 5.0);
    const auto node = radial_profile(f, sectors(m), SectorKind::node, 5.0);
    ASSERT_EQ(anti.count.size(), 8u);
    for (std::size_t k = 2; k < 8; ++k) {
      ASSERT_GT(anti.count[k], 0u);
      const double r_lo = 5.0 * static_cast<double>(k), r_hi = r_lo + 5.0;
      EXPECT_GE(anti.mean[k], std::cos(m * 5.0 * pi / 180.0) * r_lo - 1e-12);
      EXPECT_LE(anti.max[k], r_hi + 1e-12);
      EXPECT_LE(node.max[k], std::sin(m * 5.0 * pi / 180.0) * r_hi + 1e-12);
      EXPECT_LE(anti.median[k], anti.max[k]);
    }
  }
}

TEST(SectorProfile, EmptyColumnsAreSkipped) {
  GridField f = field_of([](double r, double) { return r < 20 ? std::nan("") : 1.0; });
  const auto p = radial_profile(f, sectors(2), SectorKind::antinode, 10.0);
  EXPECT_EQ(p.count[0], 0u);
  EXPECT_EQ(p.count[1], 0u);
  EXPECT_TRUE(std::isnan(p.mean[0]));
  EXPECT_GT(p.count[2], 0u);
  EXPECT_DOUBLE_EQ(p.median[2], 1.0);
}

TEST(SectorProfile, PeaksFindABumpInEachAntinodeSector) {
  // One Gaussian bump per antinode of m = 3, at distances 10, 15, ..., 35 from the axis.
  const ModeSectors s = sectors(3, 15.0);
  const GridField f = field_of([](double r, double a) {
    double h = 1.0;
    for (int k = 0; k < 6; ++k) {
      const double ak = k * pi / 3, rk = 10.0 + 5.0 * k;
      const double dx = r * std::cos(a) - rk * std::cos(ak),
                   dy = r * std::sin(a) - rk * std::sin(ak);
      h += (2.0 + k) * std::exp(-(dx * dx + dy * dy) / 4.0);
    }
    return h;
  });
  const auto peaks = sector_peaks(f, s);
  ASSERT_EQ(peaks.size(), 6u);
  for (int k = 0; k < 6; ++k) {
    EXPECT_NEAR(peaks[k].azimuth, k * pi / 3, 1e-12);
    EXPECT_NEAR(peaks[k].r, 10.0 + 5.0 * k, 1.0) << "sector " << k;
    // The highest column centre lies within sqrt(2)/2 of the bump's top.
    EXPECT_LE(peaks[k].value, 3.0 + k) << "sector " << k;
    EXPECT_GE(peaks[k].value, 1.0 + (2.0 + k) * std::exp(-0.5 / 4.0)) << "sector " << k;
  }
}

TEST(SectorProfile, RefusesImpossibleSectors) {
  const GridField f = field_of([](double, double) { return 1.0; });
  EXPECT_THROW(radial_profile(f, sectors(0), SectorKind::node, 1.0), std::invalid_argument);
  EXPECT_THROW(radial_profile(f, sectors(2, 46.0), SectorKind::node, 1.0), std::invalid_argument);
  EXPECT_THROW(radial_profile(f, sectors(2), SectorKind::node, 0.0), std::invalid_argument);
}

} // namespace
} // namespace yuxi::analysis

namespace yuxi {
namespace {

TEST(NpyRecords, HeaderFollowsTheFormatAndAlignsTheData) {
  const std::vector<NpyField> fields = {{"id", "<i8"}, {"x", "<f4"}, {"e", "<f8"}};
  const std::string h = npy_header(fields, 12345);
  ASSERT_GE(h.size(), 10u);
  EXPECT_EQ(h.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  EXPECT_EQ(h.size() % 64, 0u) << "data start on a multiple of 64 bytes";
  const std::size_t length =
      static_cast<unsigned char>(h[8]) + 256u * static_cast<unsigned char>(h[9]);
  EXPECT_EQ(length + 10, h.size());
  EXPECT_EQ(h.back(), '\n');
  EXPECT_NE(h.find("'descr': [('id', '<i8'), ('x', '<f4'), ('e', '<f8'), ]"), std::string::npos);
  EXPECT_NE(h.find("'shape': (12345,)"), std::string::npos);
  EXPECT_NE(h.find("'fortran_order': False"), std::string::npos);
  EXPECT_THROW(NpyField({"bad", "<c16"}).bytes(), std::invalid_argument);
}

TEST(NpyRecords, AFileHoldsTheHeaderThenTheRecords) {
  const auto dir = test::temp_dir("npy");
  const std::vector<NpyField> fields = {{"id", "<i8"}, {"x", "<f4"}};
  std::string records;
  for (std::int64_t id : {7, 9}) {
    const float x = 0.5f * static_cast<float>(id);
    records.append(reinterpret_cast<const char*>(&id), 8);
    records.append(reinterpret_cast<const char*>(&x), 4);
  }
  write_npy_records(Comm::self(), dir / "a.npy", fields, records);
  std::ifstream in(dir / "a.npy", std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  const std::string header = npy_header(fields, 2);
  EXPECT_EQ(bytes.str(), header + records);
  EXPECT_THROW(write_npy_records(Comm::self(), dir / "b.npy", fields, records.substr(1)),
               std::invalid_argument);
}

} // namespace
} // namespace yuxi
