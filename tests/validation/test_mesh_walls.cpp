// Mesh and cylinder walls against closed forms and against the analytic plane
// (docs/walls.md section 5):
//  - a face is a plane: a sphere bouncing off a triangle leaves it as it leaves the plane the
//    triangle lies in, to 1e-12 of the impact speed, for every contact model and angle;
//  - a meshed plane is a plane: rolling and sliding across a plane cut into thousands of
//    triangles of random shape follows the analytic plane's trajectory to 1e-9 over 1e5 steps
//    (the contacts hand their tangential springs over from triangle to triangle);
//  - a sphere at rest in a symmetric 90 degree groove loads each face with m g / sqrt(2) along
//    its normal (statics: two forces at 45 degrees balance m g); with friction each face
//    carries m g / 2 of the weight;
//  - passive meshes and cylinders never add energy, over a sweep of angles, spins and models;
//  - a servo piston compresses a bed to its target force and holds it there (to 1 %), with the
//    energy books closing;
//  - a cylinder carried down (a silo's floor lowered) takes the grains resting on it down by
//    exactly its travel, holds at t1, and books the work m g delta it took from them.
#include "core/random.hpp"
#include "core/units.hpp"
#include "mesh_surfaces.hpp"
#include "validation/impact_probe.hpp"

#include <cmath>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

using validation::Body;
using validation::Impact;

// Every contact model, with its example coefficients (model units: m = 1, a = 0.5, k_n = 1).
std::vector<AnyContactLaw> example_laws() {
  std::vector<AnyContactLaw> laws;
  ContactModels::for_each([&](auto model) {
    using Model = typename decltype(model)::type;
    ContactLaw<Model> law{PairTable<typename Model::Coeffs>(1)};
    law.coeffs.set(0, 0, ModelScene<Model>::example());
    laws.push_back(law);
  });
  return laws;
}

// A square of side 2 h in the plane through p with unit normal n, cut into two triangles.
MeshWall square(const Vec3& p, const Vec3& n, double h) {
  const Vec3 e1 = perpendicular(n);
  const Vec3 e2 = cross(n, e1);
  const Vec3 a = p - h * e1 - h * e2, b = p + h * e1 - h * e2, c = p + h * e1 + h * e2,
             d = p - h * e1 + h * e2;
  MeshWall w;
  w.name = "square";
  w.mesh = TriangleMesh::weld({{{a, b, c}}, {{a, c, d}}});
  return w;
}

// A plane z = 0 cut into triangles of random shape: an n x n grid of cells of edge h from
// (x0, y0), inner vertices shifted at random within the plane, each cell split along a random
// diagonal.
MeshWall random_triangulation(int n, double h, double x0, double y0, std::uint64_t seed) {
  return test::mesh_wall_of(
      test::random_surface(n, n, seed,
                           [&](double u, double v) {
                             return Vec3{x0 + u * (n * h), y0 + v * (n * h), 0.0};
                           }),
      "meshed plane");
}

TEST(MeshWalls, AFaceIsAPlane) {
  const Vec3 n = normalized(Vec3{0.3, -0.2, 1.0}), p{0.1, 0.2, -0.05};
  int cases = 0;
  for (const AnyContactLaw& law : example_laws())
    for (double theta : {0.0, 30.0, 60.0, 85.0}) {
      const double th = theta * pi / 180, r = 0.5, m = 1.0, speed = 0.01;
      const Vec3 t1 = normalized(cross(n, Vec3{1, 0, 0})), t2 = cross(n, t1);
      const Vec3 v = speed * (std::sin(th) * (0.8 * t1 + 0.6 * t2) - std::cos(th) * n);
      const Vec3 w = (0.3 * speed / r) * t1;
      Impact s;
      s.law = law;
      s.dt = 0.02; // t_c = pi sqrt(m*/k) ~ 3 in model units
      s.bodies.push_back({p + (r + 1.3e-4) * n, v, w, r, m});
      Impact with_plane = s, with_mesh = s;
      with_plane.planes.push_back(validation::flat_wall(p, n, 0));
      with_mesh.walls.push_back(square(p, n, 20.0));
      const auto a = validation::run_impact(with_plane), b = validation::run_impact(with_mesh);
      ASSERT_TRUE(a.separated && b.separated);
      EXPECT_LT(norm(a.v[0] - b.v[0]), 1e-12 * speed) << "model " << law.index() << " " << theta;
      EXPECT_LT(norm(a.w[0] - b.w[0]), 1e-12 * speed / r)
          << "model " << law.index() << " " << theta;
      EXPECT_EQ(a.contact_time, b.contact_time);
      EXPECT_GT(norm(a.v[0] - v), 0.1 * speed); // it did bounce
      ++cases;
    }
  EXPECT_EQ(cases, 4 * static_cast<int>(ContactModels::names.size()));
}

// One grain on the plane z = 0, as an analytic plane or as a meshed one, under gravity tilted
// by `tangential`, on contacts of stiffness k_n (resting overlap m g_z / k_n); returns its
// position, velocity and spin after `steps` steps.
struct Track {
  Vec3 x, v, w;
};
Track roll(bool meshed, Vec3 gravity, Vec3 v0, Vec3 w0, double mu, int steps, double k_n) {
  LinearSpringDashpot::Coeffs c{k_n, 2.0 / 7.0 * k_n, 20.0, 10.0, mu, mu};
  SimulationConfig cfg;
  cfg.box = {{-2, -2, -1}, {38, 38, 3}};
  cfg.gravity = gravity;
  cfg.dt = 1e-4;
  cfg.skin = 0.05;
  const double r = 0.5, m = 1.0;
  ParticleStore store;
  ParticleSpec sp;
  sp.position = {0.5, 0.5, r + m * gravity.z / k_n}; // at its resting overlap
  sp.velocity = v0;
  sp.angular_velocity = w0;
  sp.radius = r;
  sp.mass = m;
  store.add(sp, 0);
  std::vector<PlaneWall> planes;
  std::vector<ShapedWall> walls;
  if (meshed)
    walls.push_back(random_triangulation(100, 0.37, -1.0, -1.0, 7));
  else
    planes.push_back(validation::flat_wall({0, 0, 0}, {0, 0, 1}, 0));
  Simulation sim(cfg, std::move(store), planes, {}, validation::linear_law(c, 1), Comm::self(),
                 walls);
  sim.run(steps);
  const auto& s = sim.particles();
  return {s.x[0], s.v[0], s.w[0]};
}

TEST(MeshWalls, AMeshedPlaneIsAPlane) {
  // rolling with a little spin about the normal; sliding down a tilt beyond friction; resting
  // on overlaps of 0.02 %, 5 % and 20 % of the radius
  for (const double overlap : {0.0002, 0.05, 0.2})
    for (const auto& [g, v0, w0, mu] :
         {std::tuple{Vec3{0, 0, -9.81}, Vec3{0.2, 0.1, 0}, Vec3{-0.2, 0.4, 0.3}, 0.5},
          std::tuple{Vec3{0.8, 0.4, -9.81}, Vec3{0.1, 0, 0}, Vec3{}, 0.05}}) {
      const int steps = 100000;
      const double k_n = 9.81 / (overlap * 0.5);
      const Track a = roll(false, g, v0, w0, mu, steps, k_n),
                  b = roll(true, g, v0, w0, mu, steps, k_n);
      const double travel = norm(a.x - Vec3{0.5, 0.5, 0.5});
      EXPECT_GT(travel, 1.5) << "overlap " << overlap; // it crossed many triangles
      EXPECT_LT(norm(a.x - b.x), 1e-9 * travel);
      EXPECT_LT(norm(a.v - b.v), 1e-9 * norm(a.v));
      EXPECT_LT(norm(a.w - b.w), 1e-9 * (norm(a.w) + norm(a.v) / 0.5));
    }
}

// The two faces of a 90 degree groove along y (z = |x|), each its own mesh wall.
std::vector<ShapedWall> groove() {
  const double L = 3;
  MeshWall right, left;
  right.name = "right";
  left.name = "left";
  right.mesh = TriangleMesh::weld(
      {{{{0, -L, 0}, {L, -L, L}, {L, L, L}}}, {{{0, -L, 0}, {L, L, L}, {0, L, 0}}}});
  left.mesh = TriangleMesh::weld(
      {{{{0, -L, 0}, {0, L, 0}, {-L, L, L}}}, {{{0, -L, 0}, {-L, L, L}, {-L, -L, L}}}});
  return {right, left};
}

TEST(MeshWalls, AGroovesFacesShareTheWeight) {
  const double r = 0.5, m = 1.0, g = 9.81;
  for (double mu : {0.0, 0.5}) {
    LinearSpringDashpot::Coeffs c{1e5, 2.0 / 7.0 * 1e5, 200.0, 100.0, mu, mu};
    SimulationConfig cfg;
    cfg.box = {{-4, -4, -1}, {4, 4, 5}};
    cfg.gravity = {0, 0, -g};
    cfg.dt = 1e-4;
    cfg.skin = 0.05;
    ParticleStore store;
    ParticleSpec sp;
    sp.position = {0, 0, r * std::sqrt(2.0) + 0.01};
    sp.radius = r;
    sp.mass = m;
    store.add(sp, 0);
    Simulation sim(cfg, std::move(store), {}, {}, validation::linear_law(c, 1), Comm::self(),
                   groove());
    sim.run(30000);
    ASSERT_LT(norm(sim.particles().v[0]), 1e-10);
    const auto loads = sim.shaped_wall_loads();
    ASSERT_EQ(loads.size(), 2u);
    for (const WallLoad& l : loads) {
      // on the wall: without friction m g / sqrt(2) along the face's normal; with friction
      // (where friction may hold part of the load along the face) m g / 2 downwards
      if (mu == 0.0) {
        EXPECT_NEAR(norm(l.force), m * g / std::sqrt(2.0), 1e-6 * m * g);
      }
      EXPECT_NEAR(l.force.z, -m * g / 2, 1e-6 * m * g) << "mu " << mu;
    }
  }
}

double kinetic(const Vec3& v, const Vec3& w, double m, double r) {
  return 0.5 * m * norm2(v) + 0.5 * 0.4 * m * r * r * norm2(w);
}

// A box with walls on every face, under g = 9.81, with dt = 1e-4 and a skin of 0.05.
SimulationConfig walled_box(const Vec3& lo, const Vec3& hi) {
  SimulationConfig cfg;
  cfg.box = {lo, hi};
  cfg.box.boundary = {Boundary::wall, Boundary::wall, Boundary::wall};
  cfg.gravity = {0, 0, -9.81};
  cfg.dt = 1e-4;
  cfg.skin = 0.05;
  return cfg;
}

TEST(MeshWalls, PassiveMeshesAndCylindersNeverAddEnergy) {
  int impacts = 0;
  for (const AnyContactLaw& law : example_laws())
    for (bool cylinder : {false, true})
      for (double theta : {0.0, 45.0, 80.0, 89.0})
        for (double spin : {-1.0, 0.0, 1.0})
          for (double aim : {0.0, 0.37}) { // on a face, on an edge or vertex of the triangulation
            const double th = theta * pi / 180, r = 0.5, m = 1.0, speed = 0.01;
            Impact s;
            s.law = law;
            s.dt = 0.02;
            const Vec3 v = speed * Vec3{std::sin(th), 0.3 * std::sin(th), -std::cos(th)};
            const Vec3 w = (speed / r) * Vec3{spin * 0.3, spin, 0};
            if (cylinder) {
              CylinderWall c; // a drum of radius 4 about the y axis, grains inside
              c.name = "drum";
              c.axis = {0, 1, 0};
              c.center = {0, 0, 4};
              c.radius = 4;
              s.walls.push_back(c);
            } else {
              MeshWall mesh = random_triangulation(8, 0.5, -2.0 + aim, -2.0, 3);
              s.walls.push_back(mesh);
            }
            s.bodies.push_back({{0, 0, r + 1e-4}, v, w, r, m});
            const auto out = validation::run_impact(s);
            ASSERT_TRUE(out.separated);
            EXPECT_LE(kinetic(out.v[0], out.w[0], m, r), kinetic(v, w, m, r) * (1 + 1e-9))
                << "model " << law.index() << (cylinder ? " cylinder" : " mesh") << " theta "
                << theta << " spin " << spin << " aim " << aim;
            ++impacts;
          }
  EXPECT_EQ(impacts, 2 * 4 * 3 * 2 * static_cast<int>(ContactModels::names.size()));
}

TEST(MeshWalls, AServoPistonHoldsItsTargetForce) {
  // 64 grains in a 4.2 x 4.2 box with walls; a square lid comes down on them until they push
  // back with 300 (the weight of the bed is 628, carried by the floor).
  LinearSpringDashpot::Coeffs c{1e5, 2.0 / 7.0 * 1e5, 50.0, 20.0, 0.3, 0.3};
  const SimulationConfig cfg = walled_box({0, 0, 0}, {4.2, 4.2, 8});
  ParticleStore store;
  GlobalId id = 0;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        ParticleSpec sp;
        sp.position = {0.55 + 1.03 * i, 0.55 + 1.03 * j, 0.55 + 1.1 * k};
        sp.radius = 0.5;
        sp.mass = 1.0;
        store.add(sp, id++);
      }
  MeshWall lid = square({2.1, 2.1, 6.0}, {0, 0, 1}, 3.0);
  lid.name = "lid";
  const double target = 300.0;
  lid.controller = std::make_shared<ForceServo>(target, 1e-3, 0.5);
  Simulation sim(cfg, std::move(store), {}, {}, validation::linear_law(c, 1), Comm::self(), {lid});
  const double start = sim.energies().balance();
  sim.run(100000);
  double pushed = 0;
  const int samples = 5000;
  for (int k = 0; k < samples; ++k) {
    sim.step();
    pushed += sim.shaped_wall_loads()[0].force.z / samples; // the grains push the lid up
  }
  EXPECT_NEAR(pushed, target, 0.01 * target);
  const auto books = sim.energies();
  EXPECT_GT(books.wall_work, 0.0); // the lid did work on the bed
  EXPECT_LT(std::abs(books.balance() - start), 0.02 * (books.dissipated + books.wall_work));
}

TEST(MeshWalls, ACarriedFloorLowersTheGrainsOnItAndHolds) {
  // Four grains, apart, at rest on the top of a puck (a cylinder with grains outside, its top
  // cap at z = 0); from t0 = 1 to t1 = 3 the puck sinks at 0.25 (delta = 0.5, ten times the
  // skin, so the grains' wall candidates must follow it). At rest again, each grain stands
  // delta lower on the same overlap m g / k_n, and the books close on the floor's work.
  LinearSpringDashpot::Coeffs c{1e5, 2.0 / 7.0 * 1e5, 50.0, 20.0, 0.5, 0.5};
  const SimulationConfig cfg = walled_box({-4, -4, -4}, {4, 4, 4});
  ParticleStore store;
  GlobalId id = 0;
  for (const Vec3 at :
       {Vec3{-1.2, -1.2, 0.5}, Vec3{1.2, -1.2, 0.5}, Vec3{-1.2, 1.2, 0.5}, Vec3{1.2, 1.2, 0.5}}) {
    ParticleSpec sp;
    sp.position = at;
    sp.radius = 0.5;
    sp.mass = 1.0;
    store.add(sp, id++);
  }
  CylinderWall floor;
  floor.name = "floor";
  floor.radius = 2.5;
  floor.inside = false;
  floor.lo = -1, floor.hi = 0, floor.capped = true;
  const double speed = 0.25, t0 = 1.0, t1 = 3.0, delta = speed * (t1 - t0);
  floor.carried.drift = {0, 0, -speed};
  floor.carried.t0 = t0, floor.carried.t1 = t1;
  Simulation sim(cfg, std::move(store), {}, {}, validation::linear_law(c, 1), Comm::self(),
                 {floor});
  const double start = sim.energies().balance();
  sim.run(9000); // t = 0.9: settled, before the floor moves
  std::vector<double> before(4);
  for (std::size_t i = 0; i < 4; ++i) before[i] = sim.particles().x[i].z;
  EXPECT_NEAR(before[0], 0.5 - 9.81 / 1e5, 1e-6); // resting on its overlap m g / k_n
  const double work_before = sim.energies().wall_work;
  const double dissipated_before = sim.energies().dissipated;
  sim.run(31000); // t = 4: the floor stopped at t = 3
  const auto& held = std::get<CylinderWall>(sim.shaped_walls()[0]);
  EXPECT_EQ(held.shift.z, -delta);
  EXPECT_EQ(held.shift_velocity.z, 0.0);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(sim.particles().x[i].z, before[i] - delta, 1e-9) << "grain " << i;
    EXPECT_NEAR(sim.particles().v[i].z, 0.0, 1e-9);
  }
  // The floor's work: the grains' potential energy, -m g delta each, less what the two jumps of
  // its velocity dissipate. Each jump leaves a grain moving at v relative to the floor until it
  // catches up or is stopped, and that relative kinetic energy, m v^2 / 2, is dissipated: m v^2
  // per grain in all.
  const auto books = sim.energies();
  const double dissipated = books.dissipated - dissipated_before;
  EXPECT_NEAR(dissipated, 4 * speed * speed, 0.02 * 4 * speed * speed);
  EXPECT_NEAR(books.wall_work - work_before, -4 * 9.81 * delta + dissipated,
              1e-4 * 4 * 9.81 * delta);
  EXPECT_LT(std::abs(books.balance() - start), 1e-4 * 4 * 9.81 * delta);
}

} // namespace
} // namespace yuxi
