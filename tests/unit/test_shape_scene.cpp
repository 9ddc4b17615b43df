// Clumps from a scene file: [[shape]] tables (inline members or a file) and fills of them
// (io/shape_scene_reader.hpp, run/scene_builder.cpp; docs/scene-format.md, "Clumps").
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "run/scene_builder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace yuxi {
namespace {

// A box of `count` grains under gravity, as a fill of `fill_extra` (a shape, or nothing).
std::string box_scene(const std::string& shapes, const std::string& fill_extra, int count = 20) {
  return fmt::format(R"(materials = ["grain", "wall"]
[run]
name = "clumps"
dt = 1.0e-4
t_end = 0.1
[domain]
lo = [0.0, 0.0, 0.0]
hi = [8.0, 8.0, 8.0]
gravity = [0.0, 0.0, -1.0]
boundary = ["wall", "wall", "wall"]
wall_material = "wall"
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
{}
[[fill]]
material = "grain"
density = 1.0
count = {}
radius = 0.6
seed = 7
region = {{ shape = "box", lo = [0.0, 0.0, 0.0], hi = [8.0, 8.0, 8.0] }}
{}
)",
                     shapes, count, fill_extra);
}

const std::string rod = R"([[shape]]
name = "rod"
spheres = [[-0.6, 0.0, 0.0, 0.3], [0.0, 0.0, 0.0, 0.3], [0.6, 0.0, 0.0, 0.3]]
)";

std::string error_of(const std::string& text) {
  try {
    read_scene_text(text, "clumps.toml");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(ShapeScene, AFillOfAShapePlacesClumpsThatDoNotOverlap) {
  const Scene scene = read_scene_text(box_scene(rod, "shape = \"rod\""), "clumps.toml");
  ASSERT_EQ(scene.shapes.size(), 1u);
  BuildReport report;
  const auto sim = build_simulation(scene, false, &report, Comm::self());
  const auto& clumps = sim->clumps();
  ASSERT_EQ(clumps.size(), 20u);
  const ParticleStore& s = sim->particles();
  EXPECT_EQ(s.n_owned(), 60u);
  EXPECT_EQ(report.grains, 20u);
  // Each rod scaled to the fill's radius (its bounding ball: 0.9 -> 0.6), turned at random.
  const double scale = 0.6 / 0.9;
  for (const ClumpBody& b : clumps) {
    EXPECT_NEAR(b.radii[0], 0.3 * scale, 1e-12);
    EXPECT_NEAR(b.mass, scene.shapes[0].volume * scale * scale * scale, 1e-12);
  }
  EXPECT_NE(clumps[0].q, clumps[1].q);
  // No member of one clump overlaps a member of another.
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    for (std::size_t j = i + 1; j < s.n_owned(); ++j)
      if (s.body[i] != s.body[j]) {
        EXPECT_GE(norm(s.x[i] - s.x[j]), s.radius[i] + s.radius[j]) << i << " " << j;
      }
  // The time step's check takes the least mass a contact on a rod can meet.
  EXPECT_LE(report.stiffest.m_eff, 0.5 * clumps[0].smallest_contact_mass() * (1 + 1e-12));
}

// Twenty rods fall for two time units, onto the floor and each other: the books close to an
// error that shrinks with the time step (first order: the dashpot's force jumps where a
// contact begins).
TEST(ShapeScene, ClumpsFallWithTheBooksClosed) {
  const auto fall = [](double dt) {
    Scene scene = read_scene_text(box_scene(rod, "shape = \"rod\""), "clumps.toml");
    scene.sim.dt = dt;
    const auto sim = build_simulation(scene, false, nullptr, Comm::self());
    const double b0 = sim->energies().balance();
    sim->run(std::llround(2.0 / dt));
    const EnergyBooks e = sim->energies();
    EXPECT_GT(e.dissipated, 0.0);
    EXPECT_EQ(e.grains, 20u);
    return std::abs(e.balance() - b0) / e.dissipated;
  };
  const double coarse = fall(1e-4), fine = fall(2.5e-5);
  EXPECT_LT(fine, 2e-3);
  EXPECT_LT(fine, coarse / 3.0);
}

TEST(ShapeScene, AShapeOfOneSphereGivesTheSpheresBits) {
  const std::string ball = "[[shape]]\nname = \"ball\"\nspheres = [[1.0, 2.0, 3.0, 0.25]]\n";
  const auto spheres =
      build_simulation(read_scene_text(box_scene("", ""), "a.toml"), false, nullptr, Comm::self());
  const auto balls = build_simulation(
      read_scene_text(box_scene(ball, "shape = \"ball\""), "b.toml"), false, nullptr, Comm::self());
  EXPECT_TRUE(balls->clumps().empty());
  spheres->run(200);
  balls->run(200);
  const ParticleStore &a = spheres->particles(), &b = balls->particles();
  ASSERT_EQ(a.n_owned(), b.n_owned());
  for (std::size_t i = 0; i < a.n_owned(); ++i) {
    EXPECT_EQ(std::memcmp(&a.x[i], &b.x[i], sizeof(Vec3)), 0);
    EXPECT_EQ(a.mass[i], b.mass[i]);
  }
}

TEST(ShapeScene, TheEchoedSceneBuildsTheSameClumps) {
  const Scene scene = read_scene_text(box_scene(rod, "shape = \"rod\""), "clumps.toml");
  const Scene again = read_scene_text(resolved_scene_toml(scene), "echo.toml");
  const auto a = build_simulation(scene, false, nullptr, Comm::self());
  const auto b = build_simulation(again, false, nullptr, Comm::self());
  ASSERT_EQ(a->clumps().size(), b->clumps().size());
  for (std::size_t k = 0; k < a->clumps().size(); ++k) {
    EXPECT_EQ(a->clumps()[k].x, b->clumps()[k].x);
    EXPECT_EQ(a->clumps()[k].q, b->clumps()[k].q);
  }
}

TEST(ShapeScene, ClumpTablesPlaceClumpsAsWrittenTurnedAndScaled) {
  // The rod is written along x; turned a quarter about y it stands along z, twice as long.
  const std::string tables = rod + R"([[clump]]
shape = "rod"
position = [4.0, 4.0, 4.0]
orientation = [0.7071067811865476, 0.0, 0.7071067811865476, 0.0]
scale = 2.0
velocity = [1.0, 0.0, 0.0]
angular_velocity = [0.0, 0.0, 2.0]
material = "grain"
density = 1.0
)";
  const Scene scene = read_scene_text(box_scene(tables, "", 1), "clumps.toml");
  const auto sim = build_simulation(scene, false, nullptr, Comm::self());
  ASSERT_EQ(sim->clumps().size(), 1u);
  const ClumpBody& body = sim->clumps()[0];
  EXPECT_EQ(body.id, 0);
  EXPECT_EQ(body.shape, 0);
  EXPECT_NEAR(body.mass, 8.0 * scene.shapes[0].volume, 1e-12);
  const ParticleStore& p = sim->particles();
  ASSERT_EQ(p.n_owned(), 4u); // (and the fill's grain, clear of it)
  std::vector<double> heights;
  for (std::size_t i = 0; i < p.n_owned(); ++i) {
    if (p.body[i] < 0) continue;
    EXPECT_NEAR(p.x[i].x, 4.0, 1e-12);
    EXPECT_NEAR(p.x[i].y, 4.0, 1e-12);
    EXPECT_NEAR(p.radius[i], 0.6, 1e-15);
    heights.push_back(p.x[i].z);
  }
  ASSERT_EQ(heights.size(), 3u);
  std::sort(heights.begin(), heights.end());
  EXPECT_NEAR(heights[0], 2.8, 1e-12);
  EXPECT_NEAR(heights[2], 5.2, 1e-12);
  EXPECT_NEAR(norm(body.angular_velocity() - Vec3{0.0, 0.0, 2.0}), 0.0, 1e-12);
  // The echoed scene places the same bits.
  const Scene again = read_scene_text(resolved_scene_toml(scene), "echo.toml");
  const auto echoed = build_simulation(again, false, nullptr, Comm::self());
  EXPECT_EQ(echoed->clumps()[0].x, body.x);
  EXPECT_EQ(echoed->clumps()[0].q, body.q);
  EXPECT_EQ(echoed->clumps()[0].p, body.p);
}

TEST(ShapeScene, AShapeFromAFile) {
  const auto dir = std::filesystem::temp_directory_path() / "yuxi-shape-scene";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "rod.csv") << "x,y,z,radius\n-0.6,0,0,0.3\n0,0,0,0.3\n0.6,0,0,0.3\n";
  const std::string from_file = "[[shape]]\nname = \"rod\"\nfile = \"rod.csv\"\n";
  const Scene scene =
      read_scene_text(box_scene(from_file, "shape = \"rod\""), (dir / "clumps.toml").string());
  ASSERT_EQ(scene.shapes.size(), 1u);
  EXPECT_NEAR(scene.shapes[0].bounding_radius, 0.9, 1e-12);
  std::filesystem::remove_all(dir);
}

TEST(ShapeScene, BadShapesAreRefusedByName) {
  const auto refused = [](const std::string& text, const std::string& says) {
    const std::string e = error_of(text);
    EXPECT_NE(e.find(says), std::string::npos) << "error: '" << e << "', wanted: " << says;
  };
  refused(box_scene(rod, "shape = \"cube\""), "no [[shape]] named 'cube' (the scene's: rod)");
  refused(box_scene("", "shape = \"rod\""), "the scene has no [[shape]]");
  refused(box_scene(rod + rod, "shape = \"rod\""), "a second shape named 'rod'");
  refused(box_scene("[[shape]]\nname = \"x\"\n", ""), "give exactly one of 'spheres'");
  refused(box_scene("[[shape]]\nname = \"x\"\nspheres = [[0, 0, 0, -1]]\n", ""),
          "every radius must be positive");
  refused(box_scene("[[shape]]\nname = \"x\"\nspheres = [[0, 0, 0]]\n", ""),
          "row 1 has 3 numbers, not 4");
  refused(box_scene("[[shape]]\nname = \"x\"\nfile = \"no-such-file.csv\"\n", ""), "shape");
  refused(box_scene(rod, "shape = \"rod\"\nkind = \"wall\""), "wall particles are spheres");
  refused(box_scene(rod + "scale = 2.0\n", "shape = \"rod\""),
          "a shape is scaled where it is used");
  refused(box_scene("[[shape]]\nname = \"x\"\nspheres = []\n", ""), "the array is empty");
  // (allowed, with a warning: members that touch nothing of one another)
  const Scene apart = read_scene_text(
      box_scene("[[shape]]\nname = \"x\"\nspheres = [[0, 0, 0, 0.3], [2, 0, 0, 0.3]]\n", ""),
      "a.toml");
  ASSERT_EQ(apart.warnings.size(), 1u);
  EXPECT_NE(apart.warnings[0].find("shape 'x': its members make 2 separate pieces"),
            std::string::npos);
  EXPECT_TRUE(read_scene_text(box_scene(rod, ""), "a.toml").warnings.empty());
  refused(box_scene("[[shape]]\nname = \"x\"\nspheres = [[0, 0, 0, 1], [1e300, 0, 0, 1]]\n", ""),
          "member 2: radius 1 at (1e+300, 0, 0) lies beyond 1e50");
  // (a fill's own key: the places drawn for a grain, random placement only)
  EXPECT_EQ(read_scene_text(box_scene(rod, "attempts = 3"), "a.toml").fills[0].attempts_per_grain,
            3);
  refused(box_scene(rod, "attempts = 3\nplacement = \"lattice\""),
          "applies to placement = \"random\" only");
  refused(box_scene(rod + "[[insert]]\nmaterial = \"grain\"\ndensity = 1.0\nradius = 0.5\n"
                          "rate = 1.0\nshape = \"cube\"\nregion = { shape = \"box\", lo = [0.0, "
                          "0.0, 6.0], hi = [8.0, 8.0, 8.0] }\n",
                    ""),
          "no [[shape]] named 'cube' (the scene's: rod)");
}

// Rods poured from the top of a box fall into an outlet at the bottom: `insert_extra` and
// `outlet` complete the insert's and the outlet's tables.
std::string pour_scene(const std::string& shapes, const std::string& insert_extra,
                       bool outlet = true) {
  return box_scene(shapes + fmt::format(R"([[insert]]
name = "hopper"
material = "grain"
density = 1.0
radius = 0.6
rate = 60.0
interval = 0.25
total = 40
seed = 11
region = {{ shape = "box", lo = [0.0, 0.0, 5.0], hi = [8.0, 8.0, 8.0] }}
{}
{})",
                                        insert_extra,
                                        outlet ? "[[outlet]]\nname = \"floor\"\nregion = { shape "
                                                 "= \"box\", lo = [0.0, 0.0, 0.0], hi = [8.0, 8.0, "
                                                 "1.5] }\n"
                                               : ""),
                   "", 4);
}

// Every pair of spheres of different clumps (or free) apart: nothing overlaps.
void expect_no_overlap(const ParticleStore& s) {
  for (std::size_t i = 0; i < s.n_owned(); ++i)
    for (std::size_t j = i + 1; j < s.n_owned(); ++j)
      if (s.body[i] < 0 || s.body[i] != s.body[j]) {
        EXPECT_GE(norm(s.x[i] - s.x[j]), s.radius[i] + s.radius[j]) << i << " " << j;
      }
}

TEST(ShapeScene, AnInsertPoursClumpsThatDoNotOverlap) {
  const Scene scene = read_scene_text(pour_scene(rod, "shape = \"rod\""), "pour.toml");
  ASSERT_EQ(scene.inserts.size(), 1u);
  const auto sim = build_simulation(scene, false, nullptr, Comm::self());
  sim->run(1); // (the first batch: 15 rods, 0.25 time units of 60 per time unit)
  const auto& clumps = sim->clumps();
  ASSERT_EQ(clumps.size(), 15u);
  EXPECT_EQ(sim->inflow()[0].grains, 15);
  std::size_t members = 0;
  for (std::size_t i = 0; i < sim->particles().n_owned(); ++i)
    members += sim->particles().body[i] >= 0;
  EXPECT_EQ(members, 3u * 15u);
  const double scale = 0.6 / 0.9;
  double mass = 0;
  for (const ClumpBody& b : clumps) {
    EXPECT_EQ(b.shape, 0);
    EXPECT_EQ(b.members.size(), 3u);
    EXPECT_NEAR(b.radii[1], 0.3 * scale, 1e-12);
    EXPECT_NEAR(b.mass, scene.shapes[0].volume * scale * scale * scale, 1e-12);
    EXPECT_GE(b.x.z, 5.0);
    mass += b.mass;
  }
  EXPECT_NE(clumps[0].q, clumps[1].q);
  EXPECT_NEAR(sim->inflow()[0].mass, mass, 1e-12 * mass);
  expect_no_overlap(sim->particles());
  // The echoed scene pours the same rods.
  const Scene again = read_scene_text(resolved_scene_toml(scene), "echo.toml");
  ASSERT_EQ(again.inserts.size(), 1u);
  EXPECT_EQ(again.inserts[0].shape, 0);
  const auto echo = build_simulation(again, false, nullptr, Comm::self());
  echo->run(1);
  ASSERT_EQ(echo->clumps().size(), clumps.size());
  for (std::size_t b = 0; b < clumps.size(); ++b) EXPECT_EQ(echo->clumps()[b].q, clumps[b].q);
}

// 40 rods poured in three batches fall through the spheres' layer into the outlet, which takes
// each whole once its centre of mass enters: no member is left behind, each rod is counted
// once, and the books (inserted, removed, dissipated) close.
TEST(ShapeScene, AnOutletTakesClumpsWhole) {
  const Scene scene = read_scene_text(pour_scene(rod, "shape = \"rod\""), "pour.toml");
  const auto sim = build_simulation(scene, false, nullptr, Comm::self());
  const double b0 = sim->energies().balance();
  sim->run(60000);
  const auto out = sim->outflow()[0];
  EXPECT_EQ(sim->inflow()[0].grains, 40);
  EXPECT_GT(out.grains, 30);
  const std::size_t left = sim->clumps().size();
  std::size_t spheres = 0, members = 0;
  const ParticleStore& s = sim->particles();
  for (std::size_t i = 0; i < s.n_owned(); ++i) (s.body[i] < 0 ? spheres : members) += 1;
  EXPECT_EQ(members, 3 * left);
  EXPECT_EQ(static_cast<std::size_t>(out.grains), 40 - left + (4 - spheres));
  for (const ClumpBody& b : sim->clumps()) EXPECT_GE(b.x.z, 1.5);
  const EnergyBooks e = sim->energies();
  EXPECT_GT(e.inserted, 0.0);
  EXPECT_GT(e.removed, 0.0);
  EXPECT_GT(e.dissipated, 0.0);
  EXPECT_LT(std::abs(e.balance() - b0), 2e-3 * e.inserted);
}

TEST(ShapeScene, AnInsertOfAOneSphereShapeGivesTheSpheresBits) {
  const std::string ball = "[[shape]]\nname = \"ball\"\nspheres = [[1.0, 2.0, 3.0, 0.25]]\n";
  const auto spheres =
      build_simulation(read_scene_text(pour_scene("", ""), "a.toml"), false, nullptr, Comm::self());
  const auto balls =
      build_simulation(read_scene_text(pour_scene(ball, "shape = \"ball\""), "b.toml"), false,
                       nullptr, Comm::self());
  spheres->run(3000);
  balls->run(3000);
  EXPECT_TRUE(balls->clumps().empty());
  const ParticleStore &a = spheres->particles(), &b = balls->particles();
  ASSERT_EQ(a.n_owned(), b.n_owned());
  for (std::size_t i = 0; i < a.n_owned(); ++i)
    EXPECT_EQ(std::memcmp(&a.x[i], &b.x[i], sizeof(Vec3)), 0);
}

// A run continued from its state counts each clump as one grain, as the fresh start does.
TEST(ShapeScene, AContinuedRunCountsClumpsAsGrains) {
  const Scene scene = read_scene_text(box_scene(rod, "shape = \"rod\""), "clumps.toml");
  BuildReport fresh, continued;
  const auto sim = build_simulation(scene, false, &fresh, Comm::self());
  sim->run(10);
  ArchiveWriter saved;
  sim->save_state(saved);
  continue_simulation(scene, {{saved.data()}, 1}, std::nullopt, false, &continued, Comm::self());
  EXPECT_EQ(fresh.grains, 20u);
  EXPECT_EQ(continued.grains, 20u);
  EXPECT_EQ(continued.walls, 0u);
}

// A branch into a scene of other shapes finds each clump's shape by its name: the same shapes
// listed in another order, or none of them (-1: no shape of that name).
TEST(ShapeScene, ABranchFindsItsClumpsShapesByName) {
  const std::string tri = "[[shape]]\nname = \"tri\"\nspheres = [[0.0, 0.0, 0.0, 0.3], "
                          "[0.5, 0.0, 0.0, 0.3], [0.0, 0.5, 0.0, 0.3]]\n";
  const Scene scene = read_scene_text(box_scene(tri + rod, "shape = \"rod\""), "a.toml");
  const auto sim = build_simulation(scene, false, nullptr, Comm::self());
  sim->run(10);
  ArchiveWriter saved;
  sim->save_state(saved);
  ASSERT_EQ(sim->clumps().front().shape, 1); // rod, second in the scene
  const auto shapes_after = [&](const std::string& shapes) {
    // (the other scene's fill of spheres is not built: a branch takes the checkpoint's grains)
    const Scene other = read_scene_text(box_scene(shapes, ""), "b.toml");
    const auto branch = continue_simulation(other, {{saved.data()}, 1}, Simulation::BranchCheck{},
                                            false, nullptr, Comm::self());
    std::vector<std::int32_t> found;
    for (const ClumpBody& b : branch->clumps()) found.push_back(b.shape);
    return found;
  };
  EXPECT_EQ(shapes_after(rod + tri), std::vector<std::int32_t>(20, 0));
  EXPECT_EQ(shapes_after(tri), std::vector<std::int32_t>(20, -1));
  // Resumed under its own scene, as saved.
  EXPECT_EQ(shapes_after(tri + rod), std::vector<std::int32_t>(20, 1));
}

// A run that pours and drains rods, saved while batches are still to come, resumes bit for bit.
TEST(ShapeScene, ARunPouringClumpsResumesBitForBit) {
  const Scene scene = read_scene_text(pour_scene(rod, "shape = \"rod\""), "pour.toml");
  const auto first = build_simulation(scene, false, nullptr, Comm::self());
  first->run(4000);
  ArchiveWriter saved;
  first->save_state(saved);
  first->run(30000);
  const auto resumed = build_simulation(scene, false, nullptr, Comm::self());
  resumed->load({{saved.data()}, 1});
  resumed->run(30000);
  EXPECT_EQ(first->inflow()[0].grains, 40);
  EXPECT_GT(first->outflow()[0].grains, 0);
  ASSERT_EQ(first->clumps().size(), resumed->clumps().size());
  for (std::size_t b = 0; b < first->clumps().size(); ++b) {
    const ClumpBody &x = first->clumps()[b], &y = resumed->clumps()[b];
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(std::memcmp(&x.x, &y.x, sizeof x.x), 0);
    EXPECT_EQ(std::memcmp(&x.q, &y.q, sizeof x.q), 0);
  }
  EXPECT_EQ(first->energies().balance(), resumed->energies().balance());
}

} // namespace
} // namespace yuxi
