// Scene files: the shipped scenes parse, the resolved echo reads back to the same scene, and
// every kind of mistake gets one error naming the file, line, column and key.
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "run/scene_builder.hpp"

#include <filesystem>
#include <gtest/gtest.h>
#include <ostream>
#include <toml++/toml.h>

namespace yuxi {
namespace {

const char* const base_scene = R"(materials = ["grain", "wall"]

[run]
dt = 1.0e-4
t_end = 0.01

[domain]
lo = [0.0, 0.0, 0.0]
hi = [10.0, 10.0, 10.0]
boundary = ["periodic", "periodic", "wall"]
gravity = [0.0, 0.0, -1.0]
wall_material = "wall"

[contact]
model = "linear"

[[contact.pair]]
materials = ["grain", "grain"]
k_n = 2.5e5
k_t = 0.57e5
gamma_n = 100.0
mu_s = 0.8
mu_d = 0.4

[[contact.pair]]
materials = ["grain", "wall"]
k_n = 1.0e6

[[particle]]
position = [5.0, 5.0, 5.0]
radius = 1.0
mass = 1.0
material = "grain"
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(SceneReader, BaseSceneIsValidAndBuilds) {
  const Scene s = read_scene_text(base_scene, "base.toml");
  EXPECT_EQ(s.run.name, "base");
  EXPECT_EQ(s.particles.size(), 1u);
  EXPECT_EQ(s.sim.box.boundary[0], Boundary::periodic);
  auto sim = build_simulation(s, false);
  EXPECT_EQ(sim->planes().size(), 2u); // the two z faces
}

// One grain and no source: it can meet the walls, never a grain like it, so the scene needs no
// grain-grain pair, and that pair's contact time does not limit dt.
TEST(SceneReader, ALoneGrainNeedsNoPairWithItself) {
  const std::string one_grain = R"(materials = ["ball", "wall"]
[run]
dt = 1.0e-3
t_end = 1.0
[domain]
lo = [-2.0, -2.0, -1.0]
hi = [2.0, 2.0, 2.0]
gravity = [0.0, 0.0, -9.81]
[[contact.pair]]
materials = ["ball", "wall"]
k_n = 400.0
[[plane]]
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "wall"
[[particle]]
position = [0.0, 0.0, 0.5]
radius = 0.5
mass = 1.0
material = "ball"
)";
  const Scene scene = read_scene_text(one_grain, "one.toml");
  BuildReport report;
  const auto sim = build_simulation(scene, false, &report, Comm::self());
  EXPECT_EQ(report.stiffest.material_b, 1); // the wall
  // A second grain of that material could meet the first: adding one is refused.
  ParticleSpec more;
  more.position = {1.0, 1.0, 1.0};
  more.radius = 0.5;
  more.mass = 1.0;
  EXPECT_THROW(
      {
        try {
          sim->add_grains(std::vector<ParticleSpec>{more});
        } catch (const std::invalid_argument& e) {
          EXPECT_NE(std::string(e.what()).find("no contact pair for materials 0 and 0"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      std::invalid_argument);
  // Two grains need the pair.
  std::string two = one_grain + "[[particle]]\nposition = [1.0, 1.0, 0.5]\nradius = 0.5\nmass = "
                                "1.0\nmaterial = \"ball\"\n";
  EXPECT_THROW(read_scene_text(two, "two.toml"), SceneError);
}

TEST(SceneReader, ShippedScenesAreValid) {
  for (const char* name : {"basin-small", "basin-paper", "basin-paper-m3"}) {
    const Scene s = read_scene_file(std::string(YUXI_SCENES_DIR) + "/" + name + ".toml");
    EXPECT_EQ(s.run.name, name);
    ASSERT_TRUE(s.basin.has_value());
  }
}

TEST(SceneReader, ResolvedSceneReadsBackIdentically) {
  const Scene a = read_scene_file(std::string(YUXI_SCENES_DIR) + "/basin-small.toml");
  const std::string echo = resolved_scene_toml(a);
  const Scene b = read_scene_text(echo, "resolved.toml");
  const auto body = [](const std::string& t) { return t.substr(t.find("\nmaterials")); };
  EXPECT_EQ(body(resolved_scene_toml(b)), body(echo));
  EXPECT_EQ(b.sim.ranks, a.sim.ranks);
  EXPECT_EQ(b.sim.rebalance_every, a.sim.rebalance_every);
  EXPECT_EQ(b.sim.balance_by, BalanceBy::pairs);
  Scene by_time = a;
  by_time.sim.balance_by = BalanceBy::time;
  EXPECT_EQ(read_scene_text(resolved_scene_toml(by_time), "t.toml").sim.balance_by,
            BalanceBy::time);
  // Nothing is dropped: every key of the shipped scene's tables is in the resolved scene
  // (a resumed run reads its scene from there).
  const toml::table original = toml::parse_file(std::string(YUXI_SCENES_DIR) + "/basin-small.toml");
  const toml::table resolved = toml::parse(echo);
  for (const auto& [name, node] : original) {
    const auto* table = node.as_table();
    if (!table) continue;
    const auto* other = resolved[name].as_table();
    ASSERT_NE(other, nullptr) << "[" << name.str() << "] is missing";
    for (const auto& [key, value] : *table)
      EXPECT_TRUE(other->contains(key.str())) << name.str() << "." << key.str() << " is missing";
  }
  const Scene c =
      read_scene_text(resolved_scene_toml(read_scene_text(base_scene, "base.toml")), "r.toml");
  EXPECT_EQ(c.particles.size(), 1u);
}

struct BadScene {
  const char* what;
  std::string from, to;
  std::string expected; // substring of the message
  int line;             // expected line of the error (0: not checked)
};
// ctest lists a case by its name and this, not by a dump of the parameter's bytes.
void PrintTo(const BadScene& c, std::ostream* os) {
  *os << c.what;
}

class BadScenes : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadScenes, GiveOneClearError) {
  const BadScene& c = GetParam();
  const std::string text = replaced(base_scene, c.from, c.to);
  try {
    const Scene s = read_scene_text(text, "bad.toml");
    build_simulation(s, false);
    FAIL() << c.what << ": accepted";
  } catch (const SceneError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(c.expected), std::string::npos) << c.what << ": " << msg;
    if (!e.key.empty()) { // (the key's path, as the message names it)
      EXPECT_NE(msg.find(e.key), std::string::npos) << msg;
    }
    if (c.line > 0) {
      EXPECT_EQ(msg.rfind("bad.toml:" + std::to_string(c.line) + ":", 0), 0u)
          << c.what << ": " << msg;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Table, BadScenes,
    ::testing::Values(
        BadScene{"syntax", "t_end = 0.01", "t_end = = 0.01", "syntax error", 5},
        BadScene{"unknown key", "t_end = 0.01", "t_end = 0.01\ntend = 3", "run.tend: unknown key",
                 6},
        BadScene{"missing key", "dt = 1.0e-4\n", "", "[run]: missing key 'dt'", 3},
        BadScene{"wrong type", "dt = 1.0e-4", "dt = \"small\"",
                 "run.dt: expected a number, got a string", 4},
        BadScene{"negative radius", "radius = 1.0", "radius = -1.0",
                 "particle[1].radius: must be > 0", 31},
        BadScene{"zero stiffness", "k_n = 1.0e6", "k_n = 0.0", "contact.pair[2].k_n: must be > 0",
                 27},
        BadScene{"zero mass", "mass = 1.0", "mass = 0", "particle[1].mass: must be > 0", 32},
        BadScene{"mu_d above mu_s", "mu_d = 0.4", "mu_d = 0.9", "exceeds static friction", 23},
        BadScene{"unknown material", "material = \"grain\"", "material = \"sand\"",
                 "material \"sand\" is not in", 33},
        BadScene{"missing pair",
                 "[[contact.pair]]\nmaterials = [\"grain\", \"wall\"]\nk_n = 1.0e6\n", "",
                 "no [[contact.pair]] for materials (\"grain\", \"wall\")", 0},
        BadScene{"inverted domain", "hi = [10.0, 10.0, 10.0]", "hi = [10.0, -1.0, 10.0]",
                 "domain.hi: must exceed 'lo'", 9},
        BadScene{"bad boundary", "\"periodic\", \"periodic\", \"wall\"",
                 "\"periodic\", \"loop\", \"wall\"", "unknown boundary \"loop\"", 10},
        BadScene{"cell smaller than a grain", "wall_material = \"wall\"",
                 "wall_material = \"wall\"\ncell_size = 1.5",
                 "domain.cell_size: 1.5 is smaller than the largest contact distance 2", 13},
        BadScene{"outside the domain", "position = [5.0, 5.0, 5.0]", "position = [5.0, 5.0, 50.0]",
                 "particle[1].position", 30},
        BadScene{"time step too large", "dt = 1.0e-4", "dt = 1.0e-3", "run.dt: 0.001 is", 4},
        BadScene{"unknown model", "model = \"linear\"", "model = \"walton_braun\"",
                 "contact.model: unknown value \"walton_braun\"", 15},
        BadScene{"unknown balance", "wall_material = \"wall\"",
                 "wall_material = \"wall\"\nbalance_by = \"luck\"",
                 "domain.balance_by: unknown value \"luck\"", 13},
        BadScene{"misspelt optional key", "mu_d = 0.4", "mu_d = 0.4\ngama_t = 3.0",
                 "contact.pair[1].gama_t: unknown key 'gama_t' (did you mean 'gamma_t'?)", 24},
        BadScene{"rolling friction without a spring", "mu_d = 0.4", "mu_d = 0.4\nmu_r = 0.1",
                 "mu_r without k_r resists nothing in the elastic-plastic rolling model", 0},
        BadScene{"misspelt required key", "radius = 1.0", "radious = 1.0",
                 "missing key 'radius' (the table has 'radious': misspelt?)", 0}),
    [](const ::testing::TestParamInfo<BadScene>& param_info) {
      std::string n = param_info.param.what;
      for (auto& ch : n)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return n;
    });

// The [analysis] table: a window it cannot take from a basin, and malformed lists.
TEST(SceneReader, AnalysisTableErrorsNameTheKey) {
  const std::pair<std::string, std::string> cases[] = {
      {"[analysis]\nsurface_times = [1.0]\n", "analysis.period_start: give period_start"},
      {"[analysis]\nperiod_start = 0.0\nperiod_length = 1.0\nsection_heights = [1.0]\n",
       "analysis.section_heights: expected pairs"},
      {"[analysis]\nperiod_start = 0.0\nperiod_length = 1.0\nfit_a = [2.0, 0.2]\n",
       "analysis.fit_a: expected [lo, hi]"},
      {"[analysis]\nperiod_start = 0.0\nperiod_length = 1.0\nsurface_times = [\"late\"]\n",
       "analysis.surface_times"}};
  for (const auto& [table, expected] : cases) {
    const std::string text = replaced(base_scene, "[[particle]]", table + "\n[[particle]]");
    try {
      read_scene_text(text, "bad.toml");
      FAIL() << table << ": accepted";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

TEST(SceneReader, BasinLargerThanTheDomainIsRefused) {
  std::string text = std::string(base_scene);
  text = replaced(text, "[[particle]]",
                  "[basin]\ncells = [24, 24, 16]\ngrain_material = \"grain\"\nwall_material = "
                  "\"wall\"\n\n[[particle]]");
  try {
    read_scene_text(text, "bad.toml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("the container is larger than the domain"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneReader, MissingFileIsNamed) {
  try {
    read_scene_file("/nonexistent/scene.toml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.toml: cannot open"),
              std::string::npos);
  }
}

} // namespace
} // namespace yuxi
