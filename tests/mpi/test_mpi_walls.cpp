// The distributed engine gives the answers of the serial one (tests/mpi/, run with mpirun -np
// 1, 2 and 4 by ctest): turning drums, meshes held in parts, deforming and servo
// meshes, resumed bit for bit.
#include "mpi_support.hpp"

#include <gtest/gtest.h>

namespace yuxi {
namespace {

using namespace mpi_test;

// A rotating drum of radius 5 about the y axis (a mesh of 48 facets with caps, or an analytic
// capped cylinder) half full of grains: wall contacts live with their grains across ranks, move
// with them, and the run agrees with the serial one (1000 steps; grains tumble against the
// turning wall, so the tolerances are those of the other chaotic runs here: 6000 steps,
// positions to 1e-9, velocities to 1e-7, the wall's work and the books to 1e-8 and 1e-10).
Simulation rotating_drum(bool meshed, Comm comm, double omega = 0.5) {
  SimulationConfig cfg;
  cfg.box = {{-6, -0.5, -6}, {6, 3.5, 6}};
  cfg.gravity = {0, 0, -9.81};
  cfg.dt = 1e-4;
  cfg.skin = 0.1;
  cfg.ranks = {comm.size(), 1, 1};
  const double R = 5, L = 3;
  std::vector<ParticleSpec> grains;
  Random rng(5);
  for (double x = -4.2; x <= 4.2; x += 0.79)
    for (double y = 0.45; y <= L - 0.45; y += 0.79)
      for (double z = -4.5; z <= 0.0; z += 0.79)
        if (std::hypot(x, z) < R - 0.6)
          grains.push_back(test::sphere({x, y, z}, rng.uniform(0.37, 0.395), 0.3,
                                        {rng.uniform(-1, 1), rng.uniform(-1, 1), 0}));
  std::vector<ShapedWall> walls;
  if (meshed) {
    std::vector<std::array<Vec3, 3>> soup;
    const int n = 48;
    for (int k = 0; k < n; ++k) {
      const double a0 = 2 * pi * k / n, a1 = 2 * pi * (k + 1) / n;
      const Vec3 a{R * std::cos(a0), 0, R * std::sin(a0)}, b{R * std::cos(a1), 0, R * std::sin(a1)};
      const Vec3 c = b + Vec3{0, L, 0}, d = a + Vec3{0, L, 0};
      soup.push_back({a, b, c});
      soup.push_back({a, c, d});
      soup.push_back({Vec3{}, b, a});
      soup.push_back({Vec3{0, L, 0}, d, c});
    }
    MeshWall m;
    m.name = "drum";
    m.mesh = TriangleMesh::weld(soup);
    RigidMotion turn;
    turn.axis = {0, 1, 0};
    turn.omega = omega;
    if (omega != 0.0) m.motion = turn;
    walls.push_back(m);
  } else {
    CylinderWall c;
    c.name = "drum";
    c.axis = {0, 1, 0};
    c.radius = R;
    c.lo = 0, c.hi = L, c.capped = true;
    c.omega = omega;
    walls.push_back(c);
  }
  return Simulation(cfg, test::store_of(grains), {}, {},
                    test::linear_law({2e4, 2e4 * 2 / 7, 20, 10, 0.5, 0.4}), comm, walls);
}

// Of the drum's mesh, each rank holds only the triangles near its grains: fewer than the whole
// (the bed lies in the drum's lower half), and every triangle that comes within a grain's
// radius plus the skin of one of its grains.
void expect_held_in_parts(const Simulation& sim, const Comm& world, std::size_t wall = 0) {
  const auto& mesh = std::get<MeshWall>(sim.shaped_walls()[wall]);
  const TriangleMesh& whole = mesh.whole_mesh();
  EXPECT_LT(mesh.mesh.n_triangles(), whole.n_triangles()) << "rank " << world.rank();
  std::vector<char> held(whole.n_triangles(), 0);
  for (std::uint32_t t = 0; t < mesh.mesh.n_triangles(); ++t) held[mesh.element_of(t)] = 1;
  const std::vector<Vec3> at = mesh.placed_whole();
  const ParticleStore& p = sim.particles();
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    if (!p.is_grain(i)) continue;
    for (std::size_t t = 0; t < whole.n_triangles(); ++t) {
      const auto& tri = whole.triangles[t];
      const Vec3 q = closest_point_on_triangle(p.x[i], at[tri[0]], at[tri[1]], at[tri[2]]).point;
      if (norm(p.x[i] - q) < p.radius[i] + 0.1) { // (the drum's skin)
        EXPECT_TRUE(held[t]) << "rank " << world.rank() << ", triangle " << t;
      }
    }
  }
}

// The force on every triangle agrees with the serial run's (`expected`, on rank 0), and the bed
// presses on `loaded_at_least` of them or more.
void expect_same_triangle_forces(const std::vector<Vec3>& forces, const std::vector<Vec3>& expected,
                                 int loaded_at_least = 4) {
  ASSERT_EQ(forces.size(), expected.size());
  double loaded = 0;
  for (std::size_t t = 0; t < forces.size(); ++t) {
    EXPECT_LT(norm(forces[t] - expected[t]), 1e-7 * (1 + norm(expected[t]))) << "triangle " << t;
    loaded += norm(expected[t]) > 0 ? 1 : 0;
  }
  EXPECT_GE(loaded, loaded_at_least);
}

// The turning drum: a meshed one is held in parts too, chosen again where it stands at every
// list build, and its run agrees with the serial one.
TEST(Mpi, RotatingDrumMatchesTheSerialRun) {
  const Comm world = Comm::world();
  for (const bool meshed : {true, false}) {
    Simulation parallel = rotating_drum(meshed, world);
    parallel.run(6000);
    const Snapshot a = snapshot(parallel);
    const double work = parallel.shaped_wall_loads()[0].work; // collective
    std::vector<Vec3> forces;
    if (meshed) {
      expect_held_in_parts(parallel, world);
      forces = parallel.triangle_forces(0); // collective
    }
    if (world.rank() == 0) {
      Simulation serial = rotating_drum(meshed, Comm::self());
      serial.run(6000);
      const Snapshot b = snapshot(serial);
      EXPECT_GT(b.energies.contacts, 30u); // the bed has reached the wall
      EXPECT_NE(serial.shaped_wall_loads()[0].work, 0.0);
      EXPECT_NEAR(work, serial.shaped_wall_loads()[0].work,
                  1e-8 * std::abs(serial.shaped_wall_loads()[0].work))
          << (meshed ? "mesh" : "cylinder");
      EXPECT_NEAR(a.energies.balance(), b.energies.balance(),
                  1e-10 * std::abs(b.energies.balance()));
      expect_same(a, b, 1e-9, 1e-7);
      if (meshed) expect_same_triangle_forces(forces, serial.triangle_forces(0));
    }
  }
}

// The drum's mesh standing still, the bed settling in it: held in parts, and the run, its wall
// force on each triangle included, agrees with the serial one (the tolerances of the turning
// drum above).
TEST(Mpi, AStillMeshIsHeldInPartsAndTheRunMatchesTheSerialOne) {
  const Comm world = Comm::world();
  Simulation parallel = rotating_drum(true, world, 0.0);
  parallel.run(4000);
  const Snapshot a = snapshot(parallel);
  expect_held_in_parts(parallel, world);
  const std::vector<Vec3> forces = parallel.triangle_forces(0); // collective
  if (world.rank() == 0) {
    Simulation serial = rotating_drum(true, Comm::self(), 0.0);
    serial.run(4000);
    expect_same_triangle_forces(forces, serial.triangle_forces(0));
    EXPECT_NEAR(a.energies.balance(), snapshot(serial).energies.balance(),
                1e-10 * std::abs(snapshot(serial).energies.balance()));
    expect_same(a, snapshot(serial), 1e-9, 1e-7);
  }
}

// A bin on a floor: 188 grains at rest on a lattice; the bin's side a vertical cylinder mesh of
// radius 3.6 (64 facets round, 6 rings high) that deforms in the basin's radial mode from
// t = 0.1 (m = 2, dr = 0.5, omega = 5), and over the grains a servo lid (a 12 x 12 grid of
// squares, 288 triangles, at z = 4.3) that comes down at up to 5 until they push back with 400,
// about half their weight. Neither mesh moves rigidly: the part of it that a rank holds is
// chosen again at every list build, and between builds a bound on how far any point of the mesh
// can have moved says when the next one is due (MeshWall::moved2_since_build).
Simulation bin_under_servo_lid(Comm comm) {
  SimulationConfig cfg;
  cfg.box = {{-5, -5, -0.5}, {5, 5, 6}};
  cfg.gravity = {0, 0, -9.81};
  cfg.dt = 1e-4;
  cfg.skin = 0.1;
  cfg.ranks = {comm.size(), 1, 1};
  std::vector<ParticleSpec> grains;
  Random rng(11);
  for (double x = -3.2; x <= 3.2; x += 0.79)
    for (double y = -3.2; y <= 3.2; y += 0.79)
      for (double z = 0.45; z <= 2.9; z += 0.79)
        if (std::hypot(x, y) < 3.2)
          grains.push_back(test::sphere({x, y, z}, rng.uniform(0.37, 0.395), 0.3));
  const double R = 3.6, H = 5;
  const int round = 64, rings = 6;
  std::vector<std::array<Vec3, 3>> side;
  for (int k = 0; k < round; ++k)
    for (int j = 0; j < rings; ++j) {
      const double a0 = 2 * pi * k / round, a1 = 2 * pi * (k + 1) / round;
      const double z0 = H * j / rings, z1 = H * (j + 1) / rings;
      const Vec3 a{R * std::cos(a0), R * std::sin(a0), z0},
          b{R * std::cos(a1), R * std::sin(a1), z0};
      const Vec3 c{b.x, b.y, z1}, d{a.x, a.y, z1};
      side.push_back({a, b, c});
      side.push_back({a, c, d});
    }
  MeshWall wall;
  wall.name = "side";
  wall.mesh = TriangleMesh::weld(side);
  RadialCosineMotion mode;
  mode.mode = 2, mode.amplitude = 0.5, mode.omega = 5, mode.t0 = 0.1;
  wall.motion = mode;
  std::vector<std::array<Vec3, 3>> grid;
  const int n = 12;
  const double h = 9.0 / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Vec3 a{-4.5 + h * i, -4.5 + h * j, 4.3}, b = a + Vec3{h, 0, 0}, c = a + Vec3{h, h, 0},
                                                     d = a + Vec3{0, h, 0};
      grid.push_back({a, b, c});
      grid.push_back({a, c, d});
    }
  MeshWall lid;
  lid.name = "lid";
  lid.mesh = TriangleMesh::weld(grid);
  lid.controller = std::make_shared<ForceServo>(400.0, 0.02, 5.0);
  return Simulation(cfg, test::store_of(grains), {test::plane({0, 0, 0}, {0, 0, 1})}, {},
                    test::linear_law({2e4, 2e4 * 2 / 7, 20, 10, 0.5, 0.4}), comm, {wall, lid});
}

// The bin's deforming side and its servo lid are held in parts; the run agrees with the serial
// one after 3000 steps (the tolerances of the turning drum: the servo, whose speed follows the
// force summed over the ranks, couples every grain under the lid, and round-off grows past them
// by 6000). On these ranks a checkpoint written while the lid comes down at full speed (at step
// 651; the lid, not the grains at rest, calls for every list build then) resumes bit for bit to
// step 6000: the list built again at loading is the saved run's, the lid standing where it stood at
// that build. (Built with the lid where it stands at the checkpoint instead, the resumed run
// differs from the straight one.)
TEST(Mpi, DeformingAndServoMeshesAreHeldInPartsAndResumeBitForBit) {
  const Comm world = Comm::world();
  Simulation parallel = bin_under_servo_lid(world);
  parallel.run(651);
  ArchiveWriter saved;
  parallel.save_state(saved);
  parallel.run(2349);
  const Snapshot a = snapshot(parallel);
  if (world.size() > 1)
    for (std::size_t w : {0u, 1u}) expect_held_in_parts(parallel, world, w);
  const auto& lid = std::get<MeshWall>(parallel.shaped_walls()[1]);
  EXPECT_GT(lid.servo_offset, 0.2) << "the lid came down";  // (along its axis, -z)
  const double work = parallel.shaped_wall_loads()[0].work; // collective
  const std::vector<Vec3> side_forces = parallel.triangle_forces(0),
                          lid_forces = parallel.triangle_forces(1);
  parallel.run(3000); // (on, for the resume: the lid presses on)
  ArchiveWriter straight;
  parallel.save_state(straight);

  Simulation resumed = bin_under_servo_lid(world);
  resumed.load({{saved.data()}, static_cast<std::uint64_t>(world.size())});
  resumed.run(5349);
  ArchiveWriter after;
  resumed.save_state(after);
  EXPECT_TRUE(straight.data() == after.data()) << "rank " << world.rank();

  if (world.rank() == 0) {
    Simulation serial = bin_under_servo_lid(Comm::self());
    serial.run(3000);
    EXPECT_GE(serial.shaped_wall_loads()[1].contacts, 4u); // the lid presses on the bed
    EXPECT_NE(serial.shaped_wall_loads()[0].work, 0.0);
    EXPECT_NEAR(work, serial.shaped_wall_loads()[0].work,
                1e-8 * std::abs(serial.shaped_wall_loads()[0].work));
    expect_same(a, snapshot(serial), 1e-9, 1e-7);
    expect_same_triangle_forces(side_forces, serial.triangle_forces(0), 1); // (grains it hit
    expect_same_triangle_forces(lid_forces, serial.triangle_forces(1));     // fly off again)
  }
}

} // namespace
} // namespace yuxi
