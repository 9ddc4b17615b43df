// Output files: the VTK file's appended binary data and XML agree, the LAMMPS dump has the
// layout OVITO reads, and energies.csv rows match the header.
#include "io/energy_csv.hpp"
#include "io/lammps_dump_writer.hpp"
#include "io/vtk_writer.hpp"
#include "temp_folder.hpp"
#include "test_support.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>

namespace yuxi {
namespace {

namespace fs = std::filesystem;

using test::temp_dir;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

ParticleStore three_particles() {
  return test::store_of({test::sphere({1, 2, 3}, 0.5, 1.0, {0.1, 0, 0}),
                         test::sphere({4, 5, 6}, 0.75, 2.0), test::sphere({7, 8, 9}, 1.25, 3.0)});
}

TEST(VtkWriter, AppendedDataMatchesTheDeclaredArrays) {
  const auto dir = temp_dir("vtk");
  const ParticleStore s = three_particles();
  VtkSeries series(dir);
  series.write(s, 0, 0.0);
  series.write(s, 10, 0.5);
  const std::string vtu = slurp(dir / "particles_000000010.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"3\""), std::string::npos);
  EXPECT_NE(vtu.find("Name=\"velocity\" NumberOfComponents=\"3\""), std::string::npos);
  // The first appended array is the radius: an 8-byte size, then 3 doubles.
  const auto at = vtu.find("_", vtu.find("<AppendedData"));
  ASSERT_NE(at, std::string::npos);
  std::uint64_t size = 0;
  std::memcpy(&size, vtu.data() + at + 1, 8);
  EXPECT_EQ(size, 3 * sizeof(double));
  double r[3];
  std::memcpy(r, vtu.data() + at + 9, sizeof r);
  EXPECT_EQ(r[0], 0.5);
  EXPECT_EQ(r[1], 0.75);
  EXPECT_EQ(r[2], 1.25);
  EXPECT_NE(vtu.rfind("</VTKFile>"), std::string::npos);
  const std::string pvd = slurp(dir / "particles.pvd");
  EXPECT_NE(pvd.find("timestep=\"0.5\" part=\"0\" file=\"particles_000000010.vtu\""),
            std::string::npos);
  fs::remove_all(dir);
}

TEST(LammpsDump, FramesHaveTheDumpLayout) {
  const auto dir = temp_dir("dump");
  const ParticleStore s = three_particles();
  Box box{{0, 0, 0}, {10, 10, 10}, {Boundary::periodic, Boundary::open, Boundary::wall}};
  {
    LammpsDumpWriter w(dir / "d.lammpstrj", box);
    w.write(s, 0);
    w.write(s, 5);
  }
  std::istringstream in(slurp(dir / "d.lammpstrj"));
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 2u * (9 + 3));
  EXPECT_EQ(lines[0], "ITEM: TIMESTEP");
  EXPECT_EQ(lines[12 + 1], "5");
  EXPECT_EQ(lines[4], "ITEM: BOX BOUNDS pp ff ff");
  EXPECT_EQ(lines[8].rfind("ITEM: ATOMS id type radius mass x y z vx vy vz", 0), 0u);
  std::istringstream row(lines[9]);
  double id, type, radius, mass, x;
  row >> id >> type >> radius >> mass >> x;
  EXPECT_EQ(id, 0);
  EXPECT_EQ(type, 1);
  EXPECT_EQ(radius, 0.5);
  EXPECT_EQ(x, 1.0);
  fs::remove_all(dir);
}

TEST(EnergyCsv, RowsMatchTheHeader) {
  const auto dir = temp_dir("csv");
  {
    EnergyCsv csv(dir / "e.csv");
    EnergyBooks e;
    e.translational = 1.5;
    e.elastic = 0.25;
    e.dissipated = 2.0;
    e.wall_work = 1.0;
    csv.write(e);
  }
  std::istringstream in(slurp(dir / "e.csv"));
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), std::count(row.begin(), row.end(), ','));
  EXPECT_NE(header.find("balance"), std::string::npos);
  EXPECT_NE(row.find(",1.75,"), std::string::npos); // mechanical = 1.5 + 0.25
  fs::remove_all(dir);
}

} // namespace
} // namespace yuxi
