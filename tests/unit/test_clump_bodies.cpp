// The clumps' part of the engine (sim/clump_bodies.hpp): members never touch their own clump,
// a free clump keeps its angular momentum through the engine's step, a clump leaves whole, a
// checkpoint resumes a run of clumps bit for bit, bodies turned together turn as each alone, the
// members' arms kept from the placing are arms made anew, and what a member cannot do alone is
// refused.
#include "core/free_rotation.hpp"
#include "core/units.hpp"
#include "test_support.hpp"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

namespace yuxi {
namespace {

constexpr double unit_density = 3.0 / (4.0 * pi);

ClumpShape three_spheres() {
  return make_clump_shape(
      "bent",
      std::vector<SphereMember>{{{0, 0, 0}, 0.5}, {{0.6, 0, 0}, 0.4}, {{0.1, 0.55, 0.2}, 0.35}});
}

struct Clumps {
  ParticleStore store;
  std::vector<ClumpBody> bodies;
  GlobalId next = 0;
  void add(const ClumpShape& shape, const Vec3& x, const Quaternion& q, const Vec3& v = {},
           const Vec3& omega = {}) {
    const PlacedClump c = make_clump(shape, unit_density, 0, next, x, q, v, omega);
    for (const ParticleSpec& m : c.members) store.add(m, next++);
    bodies.push_back(c.body);
  }
  void add_sphere(const Vec3& x, double r, const Vec3& v = {}) {
    store.add(test::sphere(x, r, unit_density * 4.0 / 3.0 * pi * r * r * r, v), next++);
  }
};

Simulation simulate(Clumps scene, SimulationConfig cfg, std::vector<PlaneWall> planes = {}) {
  return Simulation(cfg, std::move(scene.store), std::move(planes), {},
                    test::linear_law({1e4, 2.5e3, 20.0, 10.0, 0.5, 0.5}), Comm::world(), {},
                    std::move(scene.bodies));
}

Vec3 lab_angular_momentum(const ClumpBody& b) {
  return to_lab(b.q, body_angular_momentum(b.q, b.p));
}

TEST(ClumpBodies, MembersOfOneClumpNeverTouchEachOther) {
  Clumps scene;
  scene.add(three_spheres(), {0, 0, 0}, Quaternion{});
  Simulation sim = simulate(std::move(scene), test::open_box(5, {0, 0, 0}, 1e-3));
  EXPECT_EQ(sim.neighbor_list().n_pairs(), 0u); // they overlap, and are no pair
  sim.run(100);
  EXPECT_EQ(sim.clumps()[0].v, Vec3{});
  EXPECT_EQ(sim.energies().dissipated, 0.0);
}

// Two clumps collide, off centre: momentum is kept, and the books close with the clumps'
// energies, turning included, to an error that shrinks with the time step (the dashpot's force
// jumps where a contact begins, so velocity Verlet's error is first order there, as for
// spheres): a book that missed something would not shrink.
TEST(ClumpBodies, MembersOfTwoClumpsTouch) {
  const auto collide = [](double dt) {
    Clumps scene;
    scene.add(three_spheres(), {0, 0, 0}, Quaternion{}, {1, 0, 0});
    scene.add(three_spheres(), {2.0, 0.2, 0}, about_axis({0, 0, 1}, 0.5), {-1, 0, 0});
    Simulation sim = simulate(std::move(scene), test::open_box(5, {0, 0, 0}, dt));
    const double b0 = sim.energies().balance();
    const auto& c = sim.clumps();
    const Vec3 p0 = c[0].mass * c[0].v + c[1].mass * c[1].v;
    sim.run(std::llround(2.0 / dt));
    EXPECT_LT(c[0].v.x, 0.0); // they bounced
    const Vec3 p1 = c[0].mass * c[0].v + c[1].mass * c[1].v;
    EXPECT_LT(norm(p1 - p0), 1e-12);
    const EnergyBooks e = sim.energies();
    EXPECT_GT(e.dissipated, 0.0);
    EXPECT_GT(e.rotational, 0.0);
    EXPECT_EQ(e.grains, 2u); // a clump is one grain
    return std::abs(e.balance() - b0) / e.dissipated;
  };
  const double coarse = collide(1e-4), fine = collide(2.5e-5);
  EXPECT_LT(fine, 5e-4);
  EXPECT_LT(fine, coarse / 3.0);
}

TEST(ClumpBodies, AFreeClumpKeepsItsAngularMomentumThroughTheStep) {
  Clumps scene;
  scene.add(three_spheres(), {0, 0, 0}, about_axis(normalized(Vec3{1, 2, 3}), 0.7), {0.01, 0, 0},
            {0.3, -1.1, 2.0});
  Simulation sim = simulate(std::move(scene), test::open_box(5, {0, 0, 0}, 1e-3));
  const Vec3 l0 = lab_angular_momentum(sim.clumps()[0]);
  const double e0 = sim.energies().rotational;
  sim.run(20000);
  const ClumpBody& b = sim.clumps()[0];
  EXPECT_LT(norm(lab_angular_momentum(b) - l0), 1e-12 * norm(l0));
  EXPECT_NEAR(sim.energies().rotational, e0, 1e-4 * e0); // (omega dt = 2.3e-3)
  // The members follow the body: each stands at X + R b and moves at V + omega x R b.
  const Vec3 omega = b.angular_velocity();
  for (std::size_t i = 0; i < sim.particles().n_owned(); ++i) {
    const auto k = static_cast<std::size_t>(sim.particles().gid[i] - b.id);
    EXPECT_LT(norm(sim.particles().x[i] - (b.x + b.arm(k))), 1e-12);
    EXPECT_LT(norm(sim.particles().v[i] - (b.v + cross(omega, b.arm(k)))), 1e-12);
  }
}

// The bodies turn in blocks, the sine and cosine kernels vectorised across them: each body's
// state is still that of free_rotation() between its half kicks, to the bit, for a number of
// bodies that fills no whole block, for a body at rest (zeta = 0) and for one turning so fast
// that its angles leave the kernels' range (sin_cos's reduction).
TEST(ClumpBodies, BodiesTurnedTogetherTurnAsEachAlone) {
  constexpr double dt = 0.01;
  std::vector<ClumpBody> bodies;
  for (int k = 0; k < 21; ++k) {
    const double a = 0.37 * k;
    const Vec3 omega = k == 4   ? Vec3{}
                       : k == 9 ? Vec3{900.0, -400.0, 300.0} // (omega dt / 2 > pi/4)
                                : Vec3{std::sin(a), 2.0 * std::cos(1.3 * a), 0.5 + 0.1 * k};
    PlacedClump c =
        make_clump(three_spheres(), unit_density, 0, 3 * k, {0.1 * k, 0, 0},
                   about_axis(normalized(Vec3{1.0 + a, 2.0, 3.0 - a}), a), {0.01, 0, 0}, omega);
    c.body.force = {0.2 * k, -1.0, 0.3};
    c.body.torque = {0.05, 0.01 * k, -0.2};
    bodies.push_back(c.body);
  }
  ClumpBodies together;
  together.set(bodies);
  double work = 0;
  together.kick_drift(dt, {}, work);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    ClumpBody b = bodies[k]; // alone: half kick, drift, free_rotation()
    const double kick = 0.5 * dt / b.mass;
    b.v.x += b.force.x * kick, b.v.y += b.force.y * kick, b.v.z += b.force.z * kick;
    kick_rotor(b.q, b.p, b.torque, 0.5 * dt);
    free_rotation(b.q, b.p, b.inertia, dt);
    const ClumpBody& t = together.bodies()[k];
    EXPECT_EQ(std::memcmp(&t.q, &b.q, sizeof b.q), 0) << "body " << k;
    EXPECT_EQ(std::memcmp(&t.p, &b.p, sizeof b.p), 0) << "body " << k;
  }
}

// The placing keeps each member's arm R b for the gathering of the forces and the velocities
// after the second kick: they are those of arms made anew, to the bit, and a turn of the bodies
// retires them (a gathering after a drift without a placing makes its arms anew).
TEST(ClumpBodies, ArmsKeptFromThePlacingAreArmsMadeAnew) {
  constexpr double dt = 0.01;
  Clumps scene;
  for (int k = 0; k < 11; ++k) {
    const double a = 0.41 * k;
    scene.add(three_spheres(), {1.5 * k, 0, 0}, about_axis(normalized(Vec3{1.0, a, 2.0}), a),
              {0.01 * k, 0, 0}, {std::sin(a), 0.3, 1.0 - 0.1 * k});
  }
  for (std::size_t i = 0; i < scene.store.n_owned(); ++i) {
    scene.store.f[i] = {0.1 * static_cast<double>(i), -0.2, 0.05};
    scene.store.torque[i] = {0.01, 0.02 * static_cast<double>(i), -0.03};
  }
  for (ClumpBody& b : scene.bodies) b.torque = {0.1, -0.05, 0.2};
  const auto same = [](const Vec3& a, const Vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  // `kept` reuses its arms; `anew` is given the same bodies afresh, which forgets any arms.
  ParticleStore store = scene.store, store_anew = scene.store;
  ClumpBodies kept;
  kept.set(scene.bodies);
  kept.index_members(store);
  double work = 0, moved2 = 0;
  kept.kick_drift(dt, {}, work);
  kept.place_members(store, 1.0, &moved2);
  ClumpBodies anew;
  const auto refresh = [&] {
    anew.set(kept.bodies());
    anew.index_members(store_anew);
  };
  refresh();
  kept.gather_forces(store, {0, 0, -1});
  anew.gather_forces(store_anew, {0, 0, -1});
  for (std::size_t b = 0; b < kept.size(); ++b) {
    EXPECT_TRUE(same(kept.bodies()[b].force, anew.bodies()[b].force)) << "body " << b;
    EXPECT_TRUE(same(kept.bodies()[b].torque, anew.bodies()[b].torque)) << "body " << b;
  }
  kept.final_kick(dt);
  refresh();
  kept.place_members(store, 0.0, nullptr);
  anew.place_members(store_anew, 0.0, nullptr);
  for (std::size_t i = 0; i < store.n_owned(); ++i) {
    EXPECT_TRUE(same(store.v[i], store_anew.v[i])) << "member " << i;
    EXPECT_TRUE(same(store.w[i], store_anew.w[i])) << "member " << i;
  }
  // A turn retires the arms.
  kept.kick_drift(dt, {}, work);
  refresh();
  kept.gather_forces(store, {0, 0, -1});
  anew.gather_forces(store_anew, {0, 0, -1});
  for (std::size_t b = 0; b < kept.size(); ++b)
    EXPECT_TRUE(same(kept.bodies()[b].torque, anew.bodies()[b].torque)) << "body " << b;
}

TEST(ClumpBodies, AClumpThatLeavesTheDomainLeavesWhole) {
  Clumps scene;
  scene.add(three_spheres(), {0, 0, 4.0}, Quaternion{}, {0, 0, 5.0});
  scene.add_sphere({0, 0, -3}, 0.5);
  auto cfg = test::open_box(5, {0, 0, 0}, 1e-3);
  cfg.on_escape = EscapePolicy::remove;
  Simulation sim = simulate(std::move(scene), cfg);
  const double b0 = sim.energies().balance();
  sim.run(1000);
  EXPECT_TRUE(sim.clumps().empty());
  EXPECT_EQ(sim.particles().n_owned(), 1u);
  const EnergyBooks e = sim.energies();
  EXPECT_EQ(e.escaped, 1u);
  EXPECT_NEAR(e.balance(), b0, 1e-12);
}

TEST(ClumpBodies, ACheckpointResumesARunOfClumpsBitForBit) {
  const auto build = [] {
    Clumps scene;
    for (int k = 0; k < 4; ++k)
      scene.add(three_spheres(), {-2.0 + 1.3 * k, 0.1 * k, -2.5 + 1.2 * k},
                about_axis(normalized(Vec3{1.0 * k, 1, 0.5}), 0.4 * k), {0, 0, -0.5});
    scene.add_sphere({0.3, 0.2, 2.5}, 0.4);
    auto cfg = test::open_box(4, {0, 0, -1}, 2e-4);
    cfg.box.boundary = {Boundary::periodic, Boundary::periodic, Boundary::wall};
    return simulate(std::move(scene), cfg);
  };
  Simulation first = build();
  first.run(6000);
  ArchiveWriter saved;
  first.save_state(saved);
  first.run(4000);
  Simulation resumed = build();
  resumed.load({{saved.data()}, 1});
  resumed.run(4000);
  ASSERT_EQ(first.clumps().size(), resumed.clumps().size());
  for (std::size_t b = 0; b < first.clumps().size(); ++b) {
    const ClumpBody &x = first.clumps()[b], &y = resumed.clumps()[b];
    EXPECT_EQ(std::memcmp(&x.x, &y.x, sizeof x.x), 0);
    EXPECT_EQ(std::memcmp(&x.q, &y.q, sizeof x.q), 0);
    EXPECT_EQ(std::memcmp(&x.p, &y.p, sizeof x.p), 0);
    EXPECT_EQ(std::memcmp(&x.v, &y.v, sizeof x.v), 0);
  }
  ASSERT_EQ(first.particles().n_owned(), resumed.particles().n_owned());
  for (std::size_t i = 0; i < first.particles().n_owned(); ++i)
    EXPECT_EQ(std::memcmp(&first.particles().x[i], &resumed.particles().x[i], sizeof(Vec3)), 0);
  EXPECT_GT(first.energies().dissipated, 0.0); // (they landed, not a free fall)
}

TEST(ClumpBodies, AMemberCannotBeMovedOrRemovedAlone) {
  Clumps scene;
  scene.add(three_spheres(), {0, 0, 0}, Quaternion{});
  Simulation sim = simulate(std::move(scene), test::open_box(5, {0, 0, 0}, 1e-3));
  const GlobalId member = 1;
  const Vec3 v{1, 0, 0};
  EXPECT_THROW(sim.set_velocities({&member, 1}, {&v, 1}), std::invalid_argument);
  EXPECT_THROW(sim.remove_grains({&member, 1}), std::invalid_argument);
  EXPECT_EQ(sim.particles().n_owned(), 3u);
}

// The time step's check takes a mass no larger than the effective mass of any normal push on
// any member, 1 / (1/M + (b x n) . I^-1 (b x n)) in the principal frame.
TEST(ClumpBodies, TheCheckedMassBoundsEveryNormalPush) {
  const PlacedClump c = make_clump(three_spheres(), unit_density, 0, 0, {}, Quaternion{});
  const ClumpBody& b = c.body;
  const double bound = b.smallest_contact_mass();
  Random rng(5);
  double least = 1e300;
  for (int draw = 0; draw < 20000; ++draw) {
    const Vec3 n = normalized(Vec3{rng.normal(), rng.normal(), rng.normal()});
    for (const Vec3& arm : b.members) {
      const Vec3 l = cross(arm, n);
      const double turning =
          l.x * l.x / b.inertia.x + l.y * l.y / b.inertia.y + l.z * l.z / b.inertia.z;
      least = std::min(least, 1.0 / (1.0 / b.mass + turning));
    }
  }
  EXPECT_LE(bound, least);
  EXPECT_GT(bound, 0.3 * least); // (and not far below it)
  EXPECT_LT(bound, b.mass);
}

// A state saved before particles had the `body` field (layout 9 and older) loads with every
// particle a free grain.
TEST(ClumpBodies, ParticlesOfAnOlderLayoutAreNoMembers) {
  ParticleStore old;
  old.add(test::sphere({1, 2, 3}, 0.5, 1.0, {4, 5, 6}), 7);
  old.add(test::sphere({-1, 0, 0}, 0.25, 2.0), 9);
  ArchiveWriter out;
  const std::uint64_t n = old.n_owned();
  out.value(n);
  old.for_each_field([&](const auto& field) {
    if (static_cast<const void*>(&field) != static_cast<const void*>(&old.body))
      out.elements(field.data(), n);
  });
  ParticleStore loaded;
  ArchiveReader in(out.data());
  loaded.checkpoint(in, false);
  EXPECT_TRUE(in.at_end());
  ASSERT_EQ(loaded.n_owned(), 2u);
  EXPECT_EQ(loaded.body, (std::vector<GlobalId>{-1, -1}));
  EXPECT_EQ(loaded.gid, old.gid);
  EXPECT_EQ(loaded.x, old.x);
  EXPECT_EQ(loaded.mass, old.mass);
}

TEST(ClumpBodies, AMemberWithoutItsClumpIsRefused) {
  Clumps scene;
  scene.add(three_spheres(), {0, 0, 0}, Quaternion{});
  scene.bodies.clear();
  EXPECT_THROW(simulate(std::move(scene), test::open_box(5, {0, 0, 0}, 1e-3)),
               std::invalid_argument);
}

} // namespace
} // namespace yuxi
