// Scenes in SI units and periodic boxes, written as a new user writes them: the defaults that
// depend on the grains' size (the skin), the time-step check's impact speed, and the measures,
// fills and inserts across periodic faces.
#include "io/scene_reader.hpp"
#include "run/bed_measurements.hpp"
#include "run/scene_builder.hpp"

#include <cmath>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <string>

namespace yuxi {
namespace {

// A slot hopper in metres: grains of 2.24 mm (E = 1 MPa, Hertz-Mindlin), dt = 1e-5 s, a periodic
// depth of 2.5 d, gravity 9.81 m/s^2; `extra` goes into [domain], `grains` is the [[fill]].
std::string hopper(const std::string& extra = "", double dt = 1e-5,
                   const std::string& fill = "count = 300") {
  return fmt::format(R"(materials = ["glass", "steel"]
[run]
dt = {}
t_end = 0.01
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.1, 0.0056, 0.2]
boundary = ["wall", "periodic", "wall"]
wall_material = "steel"
gravity = [0.0, 0.0, -9.81]
{}
[material.glass]
youngs_modulus = 1.0e6
poisson_ratio = 0.3
density = 2500.0
[material.steel]
youngs_modulus = 2.0e11
poisson_ratio = 0.3
[contact]
model = "hertz_mindlin"
[[contact.pair]]
materials = ["glass", "glass"]
restitution = 0.5
friction = 0.5
[[contact.pair]]
materials = ["glass", "steel"]
restitution = 0.5
friction = 0.5
[[fill]]
material = "glass"
radius = 0.00112
density = 2500.0
{}
region = {{ shape = "box", lo = [0.0, 0.0, 0.1], hi = [0.1, 0.0056, 0.15] }}
)",
                     dt, extra, fill);
}

TEST(SiScenes, TheDefaultSkinIsAFifthOfTheLargestGrainDiameter) {
  const Scene scene = read_scene_text(hopper(), "hopper.toml");
  EXPECT_DOUBLE_EQ(scene.sim.skin, 0.2 * 0.00224);
  EXPECT_TRUE(scene.warnings.empty());
  BuildReport report;
  const auto sim = build_simulation(scene, false, &report, Comm::self());
  // cells of a contact distance plus the skin: 41 across the 0.1 m width
  EXPECT_NEAR(sim->grid().edge().x, 0.1 / 37, 0.1 / 37 * 0.12);
  EXPECT_GE(sim->grid().dims()[0] - 2, 33);
}

TEST(SiScenes, ASkinTooLargeForTheGrainsIsNamed) {
  // 0.2 m, a reduced-units habit, under grains of 2.24 mm: the periodic axis is refused, and
  // the error names the skin, not the domain.
  try {
    read_scene_text(hopper("skin = 0.2"), "hopper.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("domain.skin"), std::string::npos) << m;
    EXPECT_NE(m.find("periodic axis y"), std::string::npos) << m;
  }
  // without the periodic axis it runs, with a warning that says how crowded the cells are
  std::string open = hopper("skin = 0.2");
  open.replace(open.find("\"periodic\""), 10, "\"wall\"");
  const Scene scene = read_scene_text(open, "hopper.toml");
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("[domain] skin 0.2"), std::string::npos) << scene.warnings[0];
  EXPECT_NE(scene.warnings[0].find("slower"), std::string::npos);
}

TEST(SiScenes, TheTimeStepCheckTakesTheSpeedOfAFallThroughTheScene) {
  const Scene scene = read_scene_text(hopper(), "hopper.toml");
  BuildReport report;
  build_simulation(scene, false, &report, Comm::self());
  // from the top of the highest grain (under 0.15 m) to the floor at 0
  EXPECT_GT(report.impact.speed, std::sqrt(2 * 9.81 * 0.14));
  EXPECT_LE(report.impact.speed, std::sqrt(2 * 9.81 * 0.15));
  EXPECT_NE(report.impact.source.find("a fall of"), std::string::npos) << report.impact.source;
  EXPECT_TRUE(report.stiffest.depends_on_speed);
  // At 1.7 m/s the Hertzian contact is 1.7^(1/5) = 1.11 times shorter than at 1 m/s: a dt
  // between t_c/10 at the two speeds is refused, naming the speed.
  const double tc = report.stiffest.contact_time;
  const double dt = 0.5 * (tc / 10 + tc * std::pow(report.impact.speed, 0.2) / 10);
  try {
    build_simulation(read_scene_text(hopper("", dt), "hopper.toml"), false, nullptr, Comm::self());
    FAIL() << "accepted";
  } catch (const TimeStepError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("meeting at 1."), std::string::npos) << m;
    EXPECT_NE(m.find("a fall of"), std::string::npos) << m;
  }
}

TEST(SiScenes, AMeasureAcrossAPeriodicFaceCountsTheGrainThatCrossedIt) {
  // One grain drifts across the periodic face y = 0.01: a measure of the whole box counts it
  // all along (between list builds its position stands beyond the face).
  const Scene scene = read_scene_text(R"(materials = ["g"]
[run]
dt = 1.0e-4
t_end = 0.2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.01, 0.01, 0.01]
boundary = ["open", "periodic", "open"]
gravity = [0.0, 0.0, 0.0]
skin = 0.002
[contact]
model = "hooke"
[[contact.pair]]
materials = ["g", "g"]
k_n = 10.0
[[particle]]
position = [0.005, 0.0099, 0.005]
velocity = [0.0, 0.001, 0.0]
radius = 0.001
density = 2500.0
material = "g"
[[measure]]
name = "n_box"
quantity = "grains"
region = { shape = "box", lo = [0.0, 0.0, 0.0], hi = [0.01, 0.01, 0.01] }
)",
                                      "periodic.toml");
  const auto sim = build_simulation(scene, false, nullptr, Comm::self());
  const BedMeasurements measures(scene.measures, *sim, 0.001);
  bool crossed = false;
  for (int k = 0; k < 2000; ++k) {
    sim->step();
    crossed = crossed || sim->particles().x[0].y >= 0.01;
    ASSERT_EQ(measures.values(*sim)[0], 1.0) << "step " << k + 1;
  }
  EXPECT_TRUE(crossed); // (it stood beyond the face between list builds)
}

// The smallest gap between two grains, across periodic faces too (negative: an overlap).
double smallest_gap(const ParticleStore& s, const Box& box) {
  double gap = HUGE_VAL;
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    for (std::size_t j = i + 1; j < s.n_owned(); ++j)
      gap = std::min(gap, norm(box.minimum_image(s.x[i], s.x[j])) - s.radius[i] - s.radius[j]);
  return gap;
}

TEST(SiScenes, ARandomFillAndAPourWrapAroundAPeriodicAxis) {
  // A slab 2.5 d deep: a random fill to a packing fraction of 0.27 finds room once grains may
  // straddle the periodic face (with the ball wholly inside, it stopped at 0.229), and no two
  // grains overlap across it.
  const double fraction = 0.27;
  const double volume = 0.1 * 0.0056 * 0.05;
  const int count =
      static_cast<int>(fraction * volume / (4.0 / 3.0 * 3.14159265 * std::pow(0.00112, 3)));
  const Scene scene =
      read_scene_text(hopper("", 1e-5, fmt::format("count = {}", count)), "slab.toml");
  const auto sim = build_simulation(scene, false, nullptr, Comm::self());
  EXPECT_EQ(sim->particles().n_owned(), static_cast<std::size_t>(count));
  EXPECT_GE(smallest_gap(sim->particles(), scene.sim.box), -1e-12);
  std::size_t straddling = 0;
  for (std::size_t i = 0; i < sim->particles().n_owned(); ++i) {
    const double y = sim->particles().x[i].y, r = sim->particles().radius[i];
    straddling += y < r || y > 0.0056 - r;
  }
  EXPECT_GT(straddling, static_cast<std::size_t>(count / 4));
  // A pour into the slab: batches clear of the grains there and of each other, across the face.
  std::string pour = hopper("", 1e-5, "count = 10");
  pour += R"([[insert]]
material = "glass"
radius = 0.00112
density = 2500.0
rate = 40000
total = 600
region = { shape = "box", lo = [0.0, 0.0, 0.1], hi = [0.1, 0.0056, 0.19] }
)";
  const Scene poured = read_scene_text(pour, "pour.toml");
  const auto s2 = build_simulation(poured, false, nullptr, Comm::self());
  s2->run(100); // 1 ms: 40 grains a batch
  EXPECT_GT(s2->particles().n_owned(), 30u);
  EXPECT_GE(smallest_gap(s2->particles(), poured.sim.box), -1e-6 * 0.00112);
}

} // namespace
} // namespace yuxi
