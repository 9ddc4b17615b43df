// Output files: the VTK file's appended binary data and XML agree, the LAMMPS dump has the
// layout OVITO reads, and energies.csv rows match the header.
#include "io/energy_csv.hpp"
#include "io/lammps_dump_writer.hpp"
#include "io/vtk_writer.hpp"
#include "run/wall_snapshot.hpp"
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

// The values of the appended array `name` of a .vtu file (its declared offset, an 8-byte size,
// then the values).
template <class T> std::vector<T> vtu_array(const std::string& vtu, const std::string& name) {
  const auto declared = vtu.find("Name=\"" + name + "\"");
  if (declared == std::string::npos) return {};
  const auto offset_at = vtu.find("offset=\"", declared) + 8;
  const std::size_t offset = std::stoull(vtu.substr(offset_at));
  const auto data = vtu.find("_", vtu.find("<AppendedData")) + 1;
  std::uint64_t size = 0;
  std::memcpy(&size, vtu.data() + data + offset, 8);
  std::vector<T> out(size / sizeof(T));
  std::memcpy(out.data(), vtu.data() + data + offset + 8, size);
  return out;
}

// Two rods (three spheres in a row), the second turned a quarter about z: the clumps' file
// holds their centres, orientations and principal axes, and the series names it as part 2.
TEST(VtkWriter, ClumpsGoBesideTheParticles) {
  const auto dir = temp_dir("vtk-clumps");
  const std::vector<SphereMember> rod{{{-0.6, 0, 0}, 0.3}, {{0, 0, 0}, 0.3}, {{0.6, 0, 0}, 0.3}};
  const ClumpShape shape = make_clump_shape("rod", rod);
  const Quaternion quarter = about_axis({0, 0, 1}, pi / 2);
  const PlacedClump a = make_clump(shape, 1.0, 0, 0, {1, 1, 1}, Quaternion{});
  const PlacedClump b = make_clump(shape, 1.0, 0, 3, {3, 1, 1}, quarter, {0, 0, -1}, {0, 0, 2});
  ParticleStore s;
  for (const PlacedClump* c : {&a, &b})
    for (std::size_t k = 0; k < c->members.size(); ++k)
      s.add(c->members[k], c->body.id + static_cast<GlobalId>(k));
  const std::vector<ClumpBody> bodies{a.body, b.body};
  VtkSeries series(dir);
  series.write(s, 10, 0.5, nullptr, bodies);
  const std::string vtu = slurp(dir / "clumps_000000010.vtu");
  EXPECT_NE(vtu.find("NumberOfPoints=\"2\""), std::string::npos);
  EXPECT_EQ(vtu_array<double>(vtu, "Points"), (std::vector<double>{1, 1, 1, 3, 1, 1}));
  EXPECT_EQ(vtu_array<std::int64_t>(vtu, "id"), (std::vector<std::int64_t>{0, 3}));
  const auto q = vtu_array<double>(vtu, "orientation");
  ASSERT_EQ(q.size(), 8u);
  EXPECT_EQ(q[4], b.body.q.w);
  EXPECT_EQ(q[7], b.body.q.z);
  // The rod's long axis (the smallest moment) along x, and along y once turned.
  const auto axis = vtu_array<double>(vtu, "axis_1");
  ASSERT_EQ(axis.size(), 6u);
  EXPECT_NEAR(std::abs(axis[0]), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(axis[4]), 1.0, 1e-12);
  const auto omega = vtu_array<double>(vtu, "angular_velocity");
  ASSERT_EQ(omega.size(), 6u);
  EXPECT_NEAR(omega[5], 2.0, 1e-12);
  EXPECT_EQ(vtu_array<std::int64_t>(slurp(dir / "particles_000000010.vtu"), "clump"),
            (std::vector<std::int64_t>{0, 0, 0, 3, 3, 3}));
  EXPECT_NE(slurp(dir / "particles.pvd").find("part=\"2\" file=\"clumps_000000010.vtu\""),
            std::string::npos);
  // A later frame with no clump left still has its (empty) clumps' part: ParaView would
  // otherwise keep showing the last ones.
  series.write(s, 20, 1.0, nullptr, {});
  EXPECT_NE(slurp(dir / "particles.pvd").find("part=\"2\" file=\"clumps_000000020.vtu\""),
            std::string::npos);
  EXPECT_NE(slurp(dir / "clumps_000000020.vtu").find("NumberOfPoints=\"0\""), std::string::npos);
  // The LAMMPS dump of a run with clumps names each member's clump (mol).
  LammpsDumpWriter dump(dir / "d.lammpstrj", Box{{0, 0, 0}, {5, 5, 5}}, std::nullopt, Comm::self(),
                        true);
  dump.write(s, 0);
  std::istringstream in(slurp(dir / "d.lammpstrj"));
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 9u + 6u);
  EXPECT_NE(lines[8].find("fz mol"), std::string::npos);
  EXPECT_EQ(lines[14].substr(lines[14].rfind(' ') + 1), "4"); // (clump 3, + 1)
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

// The shaped walls in the snapshots: a grain at rest on a meshed square loads it with its
// weight in walls_<step>.vtp (ASCII PolyData), which the .pvd lists as part 1 of the frame; a
// resumed series drops the later wall frames with the particle frames; without walls no .vtp
// is written and the .pvd is as before.
namespace walls_in_snapshots {

// The values of the ASCII DataArray `name` of a .vtp.
std::vector<double> ascii_array(const std::string& xml, const std::string& name) {
  const auto at = xml.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const auto from = xml.find('>', at) + 1, to = xml.find("</DataArray>", from);
  std::istringstream in(xml.substr(from, to - from));
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

std::int64_t attribute(const std::string& xml, const std::string& name) {
  const auto at = xml.find(name + "=\"");
  return at == std::string::npos ? -1 : std::stoll(xml.substr(at + name.size() + 2));
}

bool has_vtp(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".vtp") return true;
  return false;
}

} // namespace walls_in_snapshots

TEST(VtkWalls, AMeshCarriesTheWeightOfTheGrainOnIt) {
  using namespace walls_in_snapshots;
  const double r = 0.5, m = 1.0, g = 9.81, k_n = 1e5;
  // The square [-2, 2]^2 at z = 0 cut into 2 x 2 cells of two triangles (area 2 each).
  std::vector<std::array<Vec3, 3>> soup;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const double x = -2.0 + 2 * i, y = -2.0 + 2 * j;
      const Vec3 a{x, y, 0}, b{x + 2, y, 0}, c{x + 2, y + 2, 0}, d{x, y + 2, 0};
      soup.push_back({a, b, c});
      soup.push_back({a, c, d});
    }
  MeshWall floor;
  floor.name = "floor";
  floor.mesh = TriangleMesh::weld(soup);
  // One grain at its resting overlap on a face, settled by a damped linear law.
  auto cfg = test::open_box(3.0, {0, 0, -g}, 1e-4);
  const ParticleStore store = test::store_of({test::sphere({0.7, -0.4, r - m * g / k_n}, r, m)});
  Simulation sim(cfg, store, {}, {},
                 test::linear_law({k_n, 2.0 / 7.0 * k_n, 200.0, 100.0, 0.5, 0.5}), Comm::self(),
                 {floor});

  const auto dir = temp_dir("vtk_walls");
  VtkSeries series(dir);
  const WallSurface first = wall_surface(sim);
  series.write(sim.particles(), sim.step_count(), sim.time(), &first);
  sim.run(5000);
  const WallSurface surface = wall_surface(sim);
  series.write(sim.particles(), sim.step_count(), sim.time(), &surface);

  const std::string vtp = slurp(dir / "walls_000005000.vtp");
  ASSERT_NE(vtp.rfind("</VTKFile>"), std::string::npos);
  EXPECT_EQ(attribute(vtp, "NumberOfPolys"), 8);
  EXPECT_EQ(attribute(vtp, "NumberOfPoints"), 9);
  const std::vector<double> force = ascii_array(vtp, "force"),
                            pressure = ascii_array(vtp, "pressure"),
                            wall = ascii_array(vtp, "wall"), points = ascii_array(vtp, "Points"),
                            connectivity = ascii_array(vtp, "connectivity"),
                            offsets = ascii_array(vtp, "offsets");
  ASSERT_EQ(force.size(), 3u * 8);
  ASSERT_EQ(pressure.size(), 8u);
  EXPECT_EQ(wall, std::vector<double>(8, 0.0));
  EXPECT_EQ(points.size(), 3u * 9);
  EXPECT_EQ(connectivity.size(), 3u * 8);
  EXPECT_EQ(offsets.back(), 24.0);
  Vec3 total;
  int loaded = 0;
  for (std::size_t k = 0; k < 8; ++k) {
    const Vec3 f{force[3 * k], force[3 * k + 1], force[3 * k + 2]};
    total += f;
    if (f == Vec3{}) {
      EXPECT_EQ(pressure[k], 0.0);
      continue;
    }
    ++loaded;
    EXPECT_NEAR(pressure[k], std::abs(f.z) / 2.0, 1e-12 * m * g); // normal z, area 2
  }
  EXPECT_GE(loaded, 1);
  // The grain's weight, on the wall, downwards; as walls.csv has it.
  EXPECT_NEAR(total.x, 0.0, 1e-9 * m * g);
  EXPECT_NEAR(total.y, 0.0, 1e-9 * m * g);
  EXPECT_NEAR(total.z, -m * g, 1e-9 * m * g);
  EXPECT_LT(norm(total - sim.shaped_wall_loads()[0].force), 1e-12 * m * g);

  // Both parts of each frame in the collection.
  const std::string pvd = slurp(dir / "particles.pvd");
  EXPECT_NE(pvd.find("part=\"0\" file=\"particles_000005000.vtu\""), std::string::npos);
  EXPECT_NE(pvd.find("part=\"1\" file=\"walls_000005000.vtp\""), std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"0\" part=\"1\" file=\"walls_000000000.vtp\""), std::string::npos);

  // Resumed after step 0: the later frame's files go, the first frame's stay.
  VtkSeries resumed(dir, "particles", 0);
  EXPECT_FALSE(fs::exists(dir / "walls_000005000.vtp"));
  EXPECT_FALSE(fs::exists(dir / "particles_000005000.vtu"));
  EXPECT_TRUE(fs::exists(dir / "walls_000000000.vtp"));
  const std::string kept = slurp(dir / "particles.pvd");
  EXPECT_NE(kept.find("part=\"1\" file=\"walls_000000000.vtp\""), std::string::npos);
  EXPECT_EQ(kept.find("000005000"), std::string::npos);
  resumed.write(sim.particles(), sim.step_count(), sim.time(), &surface);
  EXPECT_EQ(slurp(dir / "particles.pvd"), pvd);
  fs::remove_all(dir);
}

TEST(VtkWalls, NoWallsNoWallFiles) {
  using namespace walls_in_snapshots;
  const auto dir = temp_dir("vtk_no_walls");
  VtkSeries series(dir);
  series.write(three_particles(), 0, 0.0);
  series.write(three_particles(), 10, 0.5);
  EXPECT_FALSE(has_vtp(dir));
  EXPECT_EQ(slurp(dir / "particles.pvd"),
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0\" part=\"0\" file=\"particles_000000000.vtu\"/>\n"
            "    <DataSet timestep=\"0.5\" part=\"0\" file=\"particles_000000010.vtu\"/>\n"
            "  </Collection>\n</VTKFile>\n");
  fs::remove_all(dir);
}

TEST(VtkWalls, CylindersAreCutIntoTriangles) {
  const Box box{{-2, -2, -3}, {2, 2, 5}};
  CylinderWall endless; // about z, infinite: cut at the box's ends
  endless.center = {0, 0, 1};
  endless.radius = 1.5;
  CylinderWall drum; // about y, capped between -1 and 2, turned by omega t
  drum.axis = {0, 1, 0};
  drum.radius = 1.0;
  drum.lo = -1;
  drum.hi = 2;
  drum.capped = true;
  drum.omega = 0.5;
  WallSurface s;
  s.add_cylinder(endless, box, 0.0, 0);
  ASSERT_EQ(s.triangles.size(), 2u * 64);
  ASSERT_EQ(s.points.size(), 2u * 64);
  for (const Vec3& p : s.points) {
    EXPECT_NEAR(std::hypot(p.x, p.y), 1.5, 1e-12);
    EXPECT_TRUE(p.z == -3.0 || p.z == 5.0) << p.z;
  }
  s.add_cylinder(drum, box, 1.0, 1);
  ASSERT_EQ(s.triangles.size(), 2u * 64 + 4u * 64);
  ASSERT_EQ(s.points.size(), 4u * 64 + 2);
  for (std::size_t k = 2 * 64; k < s.points.size(); ++k) {
    const Vec3& p = s.points[k];
    EXPECT_TRUE(p.y == -1.0 || p.y == 2.0) << p.y;
    if (std::hypot(p.x, p.z) > 1e-12) {
      EXPECT_NEAR(std::hypot(p.x, p.z), 1.0, 1e-12);
    }
  }
  EXPECT_EQ(std::count(s.wall.begin(), s.wall.end(), 1), 4 * 64);
  // The seam turned by omega t = 0.5 rad about y (from e1 = -z towards e2 = -x).
  EXPECT_LT(norm(s.points[2 * 64] - Vec3{-std::sin(0.5), -1, -std::cos(0.5)}), 1e-12);
  double area = 0.0;
  for (std::size_t k = 0; k < s.triangles.size(); ++k) {
    const auto& t = s.triangles[k];
    area += 0.5 * norm(cross(s.points[t[1]] - s.points[t[0]], s.points[t[2]] - s.points[t[0]]));
    EXPECT_EQ(s.pressure(k), 0.0);
  }
  const double polygon =
      0.5 * 64 * std::sin(2 * std::numbers::pi / 64); // area of the 64-gon of radius 1
  EXPECT_NEAR(area, 2 * 64 * std::sin(std::numbers::pi / 64) * (1.5 * 8 + 1.0 * 3) + 2 * polygon,
              1e-9);
}

} // namespace
} // namespace yuxi
