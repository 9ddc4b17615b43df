// [[measure]]: what measurements.csv reports against beds whose answers are known: the mass,
// count and kinetic energy of the grains in a region, the free surface's height and the angle of
// a ramp built at a known slope (planar and about an axis), and a resting grain's weight on the
// floor it stands on.
#include "core/units.hpp"
#include "io/scene_reader.hpp"
#include "run/bed_measurements.hpp"
#include "run/scene_builder.hpp"
#include "test_support.hpp"

#include <cmath>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <tuple>

namespace yuxi {
namespace {

const char* const head = R"(materials = ["grain", "wall"]
[run]
dt = 1.0e-4
t_end = 1.0
[domain]
lo = [0.0, 0.0, 0.0]
hi = [40.0, 40.0, 40.0]
gravity = [0.0, 0.0, -1.0]
[contact]
model = "linear"
[[contact.pair]]
materials = ["grain", "grain"]
k_n = 1.0e4
gamma_n = 20.0
[[contact.pair]]
materials = ["grain", "wall"]
k_n = 1.0e4
gamma_n = 20.0
[[plane]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "wall"
)";

std::string grain(const Vec3& x, double vx = 0.0) {
  return fmt::format("[[particle]]\nposition = [{}, {}, {}]\nvelocity = [{}, 0.0, 0.0]\n"
                     "radius = 0.5\nmass = 2.0\nmaterial = \"grain\"\n",
                     x.x, x.y, x.z, vx);
}

std::string measure(const std::string& body) {
  return "[[measure]]\n" + body + "\n";
}

std::vector<double> measured(const std::string& text) {
  const Scene scene = read_scene_text(text, "bed.toml");
  auto sim = build_simulation(scene, false);
  const BedMeasurements m(scene.measures, *sim, 0.5);
  return m.values(*sim);
}

TEST(BedMeasurements, MassCountAndKineticEnergyInARegion) {
  std::string text = head;
  for (int i = 0; i < 10; ++i) text += grain({2.0 + 2 * i, 5.0, 0.5}, i < 4 ? 1.0 : 0.0);
  text += measure("name = \"m\"\nquantity = \"mass\"\n"
                  "region = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [9.0, 10.0, 2.0] }");
  text += measure("name = \"n\"\nquantity = \"grains\"\n"
                  "region = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [9.0, 10.0, 2.0] }");
  text += measure("name = \"ke\"\nquantity = \"kinetic_per_grain\"");
  const auto v = measured(text);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_DOUBLE_EQ(v[0], 8.0); // grains at x = 2, 4, 6, 8
  EXPECT_DOUBLE_EQ(v[1], 4.0);
  EXPECT_DOUBLE_EQ(v[2], 4 * 0.5 * 2.0 * 1.0 / 10); // four of ten move at 1
}

// A clump is one grain: counted once, where its centre of mass stands, with its whole mass and
// its energy of motion, turning included (its members have no inertia of their own).
TEST(BedMeasurements, AClumpIsOneGrainOfItsWholeMassAndMotion) {
  std::string text = head;
  text += measure("name = \"m\"\nquantity = \"mass\"\n"
                  "region = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [9.0, 10.0, 10.0] }");
  text += measure("name = \"n\"\nquantity = \"grains\"\n"
                  "region = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [9.0, 10.0, 10.0] }");
  text += measure("name = \"ke\"\nquantity = \"kinetic_per_grain\"");
  const Scene scene = read_scene_text(text, "bed.toml");
  const ClumpShape rod = make_clump_shape(
      "rod", std::vector<SphereMember>{{{-0.5, 0, 0}, 0.5}, {{0, 0, 0}, 0.5}, {{0.5, 0, 0}, 0.5}});
  ParticleStore store;
  std::vector<ClumpBody> bodies;
  GlobalId next = 0;
  // One rod at rest in the region, one turning and moving beyond it, a sphere at rest in it.
  for (const auto& [x, v, omega] : {std::tuple{Vec3{5, 5, 3}, Vec3{}, Vec3{}},
                                    std::tuple{Vec3{20, 5, 3}, Vec3{1, 0, 0}, Vec3{0, 0.5, 2}}}) {
    const PlacedClump c = make_clump(rod, 1.0, 0, next, x, Quaternion{}, v, omega);
    for (const ParticleSpec& m : c.members) store.add(m, next++);
    bodies.push_back(c.body);
  }
  store.add(test::sphere({5, 5, 6}, 0.5, 2.0), next++);
  const ClumpBody moving = bodies[1];
  const double mass = bodies[0].mass;
  const Vec3 w_body = to_body(moving.q, moving.angular_velocity());
  const double turning =
      0.5 * (moving.inertia.x * w_body.x * w_body.x + moving.inertia.y * w_body.y * w_body.y +
             moving.inertia.z * w_body.z * w_body.z);
  Simulation sim(test::open_box(40, {0, 0, 0}, 1e-4), std::move(store), {}, {},
                 test::linear_law({1e4, 20, 0, 0, 0, 0}), Comm::world(), {}, std::move(bodies));
  const auto v = BedMeasurements(scene.measures, sim, 0.5).values(sim);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_DOUBLE_EQ(v[0], mass + 2.0);
  EXPECT_DOUBLE_EQ(v[1], 2.0);
  EXPECT_NEAR(v[2], (0.5 * mass * 1.0 + turning) / 3.0, 1e-12 * v[2]);
  EXPECT_GT(turning, 0.0);
}

TEST(BedMeasurements, TheAngleAndHeightOfARampOfKnownSlope) {
  // columns of grains one diameter apart, each as high as 0.5 x (26.57 degrees): the tops lie
  // on h = 0.5 x + 0.5 (+- half a grain where a column's height is rounded to whole grains)
  std::string text = head;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 4; ++j) {
      const double x = 1.0 + i, h = 0.5 * x;
      for (int k = 0; k < static_cast<int>(std::round(h)) + 1; ++k)
        text += grain({x, 10.0 + j, 0.5 + k});
    }
  text += measure("name = \"slope\"\nquantity = \"angle\"\ndirection = [1.0, 0.0, 0.0]\nbin = 1.0");
  text += measure("name = \"top\"\nquantity = \"surface_height\"\nbin = 1.0\n"
                  "region = { shape = \"box\", lo = [9.5, 0.0, 0.0], hi = [10.5, 40.0, 40.0] }");
  const auto v = measured(text);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NEAR(v[0], std::atan(0.5) * 180 / pi, 0.5);
  EXPECT_GT(v[1], 0.98);                   // R^2
  EXPECT_DOUBLE_EQ(v[2], 0.5 + 5.0 + 0.5); // x = 10: 6 grains, the top at 6
}

TEST(BedMeasurements, TheAngleOfAConeAboutItsAxis) {
  // a cone of grains about (20, 20) falling off at 1 in 1 (45 degrees)
  std::string text = head;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const double x = 0.5 + i, y = 0.5 + j, r = std::hypot(x - 20, y - 20);
      if (r > 10) continue;
      for (int k = 0; k <= static_cast<int>(std::round(10 - r)); ++k)
        text += grain({x, y, 0.5 + k});
    }
  text += measure("name = \"cone\"\nquantity = \"angle\"\naxis_point = [20.0, 20.0, 0.0]\n"
                  "bin = 1.0\nfrom = 1.0\nto = 9.0");
  const auto v = measured(text);
  EXPECT_NEAR(v[0], 45.0, 1.5);
  EXPECT_GT(v[1], 0.95);
}

TEST(BedMeasurements, AGrainAtRestPressesTheFloorWithItsWeight) {
  std::string text = head + grain({5.0, 5.0, 0.5});
  text += measure("name = \"floor\"\nquantity = \"wall_force\"\nwall = \"floor\"");
  const Scene scene = read_scene_text(text, "bed.toml");
  auto sim = build_simulation(scene, false);
  sim->run(20000); // the damped bounce dies out
  const BedMeasurements m(scene.measures, *sim, 0.5);
  const auto v = m.values(*sim);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NEAR(v[2], -2.0, 1e-6); // m g downward
  EXPECT_NEAR(v[0], 0.0, 1e-12);
}

TEST(BedMeasurements, MistakesAreNamedAtTheirKey) {
  const auto error = [](const std::string& body) -> std::string {
    try {
      read_scene_text(std::string(head) + measure(body), "bed.toml");
    } catch (const SceneError& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(error("name = \"f\"\nquantity = \"wall_force\"\nwall = \"roof\"")
                .find("no wall named "
                      "'roof'"),
            std::string::npos);
  EXPECT_NE(error("name = \"a b\"\nquantity = \"mass\"").find("CSV column name"),
            std::string::npos);
  EXPECT_NE(error("name = \"a\"\nquantity = \"angle\"\ndirection = [0.0, 1.0, 1.0]")
                .find("must be horizontal"),
            std::string::npos);
  EXPECT_NE(error("name = \"a\"").find("quantity"), std::string::npos);
  EXPECT_NE(error("name = \"a\"\nquantity = \"volume\"").find("quantity"), std::string::npos);
}

} // namespace
} // namespace yuxi
